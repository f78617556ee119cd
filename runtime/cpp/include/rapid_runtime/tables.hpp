// An asset as plain data: what generated code fills in as constants (the C++ twin of the
// Python runtime's asset_tables.py). Aggregates only, so a generated file can spell a
// whole asset as one brace initializer; lookups are the runtime's.
#ifndef RAPID_RUNTIME_TABLES_HPP
#define RAPID_RUNTIME_TABLES_HPP

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "value.hpp"

namespace rapid_runtime {

struct Param {
    std::string name;  // as in the descriptor (KeyTypePair.key); arguments are matched by position
    DataType type = DataType::Bool;
    std::string unit;
    std::optional<double> min;
    std::optional<double> max;
    std::vector<Value> allowed;  // empty: any value
    std::optional<Value> default_value;
    std::string description;
};

struct CommandSpec {
    std::string name;
    std::vector<Param> params;  // in the order arguments are sent
    bool abortable = false;
    bool suspendable = false;
    bool standard = false;  // a standard RAPID subsystem type's command (built-ins apply)
    std::string description;
};

struct SubsystemType {
    std::string name;
    std::vector<CommandSpec> commands;
};

struct Subsystem {
    std::string name;
    std::string type;  // a SubsystemType's name
};

// The descriptor's allow-list: which cmdSrc may send which "Subsystem/command" (patterns
// "*", "Sub/*", "*/cmd", "Sub/cmd").
struct AccessRule {
    std::string source;
    std::vector<std::string> allow;
};

struct AccessSpec {
    bool allow_by_default = false;  // for sources no rule names
    std::vector<AccessRule> rules;
};

// A command of the dictionary as found for a subsystem.
struct CommandRef {
    const SubsystemType* type = nullptr;
    const CommandSpec* spec = nullptr;
    explicit operator bool() const { return spec != nullptr; }
};

struct Tables {
    std::string name;  // the asset (hdr.assetName of its commands)
    std::string kind;
    int domain = 0;
    std::string partition;
    std::vector<Subsystem> subsystems;  // in CommandConfig order
    std::vector<SubsystemType> types;
    std::optional<AccessSpec> access;  // none: any source may command

    const std::string* type_of(std::string_view subsystem) const;
    const SubsystemType* subsystem_type(std::string_view type) const;
    CommandRef command(std::string_view subsystem, std::string_view name) const;
    bool has_type(std::string_view type) const;
    std::vector<std::string> subsystems_of_type(std::string_view type) const;
};

}  // namespace rapid_runtime

#endif
