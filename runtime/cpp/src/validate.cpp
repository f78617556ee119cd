#include "rapid_runtime/validate.hpp"

#include "rapid_runtime/text.hpp"
#include "rapid_runtime/texts.hpp"

namespace rapid_runtime {

Checked check_command(const Cmd& cmd, const Tables& tables) {
    if (tables.type_of(cmd.subsystem) == nullptr) return {{}, texts::unknown_subsystem(shorten(cmd.subsystem))};
    CommandRef ref = tables.command(cmd.subsystem, cmd.name);
    if (!ref)
        return {{}, texts::unknown_command(shorten(cmd.name), shorten(cmd.subsystem))};
    const auto& params = ref.spec->params;
    const auto got = static_cast<long long>(cmd.args.size());
    if (cmd.args.size() != params.size())
        return {ref, params.size() == 1
                         ? texts::argument_count_one(ref.spec->name, got)
                         : texts::argument_count(ref.spec->name, static_cast<long long>(params.size()), got)};
    for (std::size_t i = 0; i < params.size(); ++i) {
        if (type_of(cmd.args[i]) != params[i].type)
            return {ref, texts::argument_type(static_cast<long long>(i + 1), shorten(params[i].name, 16),
                                              std::string(name_of(params[i].type)),
                                              std::string(name_of(type_of(cmd.args[i]))))};
    }
    for (std::size_t i = 0; i < params.size(); ++i) {
        auto why = shape_error(cmd.args[i]);
        if (!why) why = limit_error(params[i], cmd.args[i]);
        if (why) return {ref, texts::argument_invalid(static_cast<long long>(i + 1), shorten(params[i].name, 16), *why)};
    }
    return {ref, std::nullopt};
}

}  // namespace rapid_runtime
