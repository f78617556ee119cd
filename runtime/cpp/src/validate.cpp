#include "rapid_runtime/validate.hpp"

#include "rapid_runtime/text.hpp"

namespace rapid_runtime {

Checked check_command(const Cmd& cmd, const Tables& tables) {
    if (tables.type_of(cmd.subsystem) == nullptr) return {{}, "unknown subsystem '" + shorten(cmd.subsystem) + "'"};
    CommandRef ref = tables.command(cmd.subsystem, cmd.name);
    if (!ref)
        return {{}, "unknown command '" + shorten(cmd.name) + "' for subsystem '" + shorten(cmd.subsystem) + "'"};
    const auto& params = ref.spec->params;
    if (cmd.args.size() != params.size())
        return {ref, ref.spec->name + " takes " + std::to_string(params.size()) + " argument" +
                         (params.size() != 1 ? "s" : "") + ", got " + std::to_string(cmd.args.size())};
    for (std::size_t i = 0; i < params.size(); ++i) {
        if (type_of(cmd.args[i]) != params[i].type)
            return {ref, "argument " + std::to_string(i + 1) + " (" + shorten(params[i].name, 16) + ") must be " +
                             std::string(name_of(params[i].type)) + ", got " +
                             std::string(name_of(type_of(cmd.args[i])))};
    }
    for (std::size_t i = 0; i < params.size(); ++i) {
        auto why = shape_error(cmd.args[i]);
        if (!why) why = limit_error(params[i], cmd.args[i]);
        if (why) return {ref, "argument " + std::to_string(i + 1) + " (" + shorten(params[i].name, 16) + "): " + *why};
    }
    return {ref, std::nullopt};
}

}  // namespace rapid_runtime
