#include "rapid_runtime/tables.hpp"

namespace rapid_runtime {

const std::string* Tables::type_of(std::string_view subsystem) const {
    for (const auto& s : subsystems)
        if (s.name == subsystem) return &s.type;
    return nullptr;
}

const SubsystemType* Tables::subsystem_type(std::string_view type) const {
    for (const auto& t : types)
        if (t.name == type) return &t;
    return nullptr;
}

CommandRef Tables::command(std::string_view subsystem, std::string_view name) const {
    const std::string* type = type_of(subsystem);
    const SubsystemType* t = type ? subsystem_type(*type) : nullptr;
    if (t == nullptr) return {};
    for (const auto& c : t->commands)
        if (c.name == name) return {t, &c};
    return {};
}

bool Tables::has_type(std::string_view type) const {
    for (const auto& s : subsystems)
        if (s.type == type) return true;
    return false;
}

std::vector<std::string> Tables::subsystems_of_type(std::string_view type) const {
    std::vector<std::string> out;
    for (const auto& s : subsystems)
        if (s.type == type) out.push_back(s.name);
    return out;
}

const TelemetryTopic* TelemetrySpec::topic(std::string_view role) const {
    for (const auto& t : topics)
        if (t.role == role) return &t;
    return nullptr;
}

const TelemetrySpec* Tables::telemetry_of(std::string_view kind, std::size_t index) const {
    for (const auto& t : telemetry)
        if (t.kind == kind && index-- == 0) return &t;
    return nullptr;
}

std::size_t Tables::count_of(std::string_view kind) const {
    std::size_t n = 0;
    for (const auto& t : telemetry) n += t.kind == kind ? 1 : 0;
    return n;
}

}  // namespace rapid_runtime
