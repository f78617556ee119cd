// An asset as plain data: what generated code fills in as constants (the C++ twin of the
// Python runtime's asset_tables.py). Aggregates only, so a generated file can spell a
// whole asset as one brace initializer; lookups are the runtime's.
#ifndef RAPID_RUNTIME_TABLES_HPP
#define RAPID_RUNTIME_TABLES_HPP

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
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
    int stop_timeout_ms = 0;  // 0: the bridge's default (--stop-timeout)
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

// A topic of a telemetry entry: its role (config, state, sample), name and QoS profile.
struct TelemetryTopic {
    std::string role;
    std::string topic;
    std::string qos;  // profile name in the generated Fast DDS XML
};

struct Joint {
    std::string frame;  // JointDef.frameName
    std::string dof;
    std::string unit;
    std::optional<double> min;
    std::optional<double> max;
};

// One telemetry entry of the descriptor (kind agent, position, joint, image, text or
// custom), with what each kind declares; the rest stays empty.
struct TelemetrySpec {
    std::string kind;
    std::vector<TelemetryTopic> topics;
    std::optional<double> rate;  // Hz; none: on change only
    std::string subsystem;
    std::vector<Param> values;  // agent and position value keys, in valueKeys order
    // position
    std::string frame;
    std::string pose_encoding;  // RotationEncoding enumerator name
    std::string velocity_encoding;
    // joint
    std::string group;
    std::vector<std::string> fields;
    std::vector<Joint> joints;
    // image
    std::string sensor;
    std::string sensor_type;
    std::string mime;
    int width = 0;
    int height = 0;
    // text
    std::vector<std::string> categories;
    // custom: role -> DDS type name (the message types the generated code publishes)
    std::vector<std::pair<std::string, std::string>> types;
    // the descriptor's stale_after_ms (ms); 0: not declared, derived from the rate (freshness.hpp)
    double stale_after_ms = 0;

    // The topic of a role, or nullptr.
    const TelemetryTopic* topic(std::string_view role) const;
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
    std::vector<TelemetrySpec> telemetry;  // the descriptor's telemetry entries, in order

    const std::string* type_of(std::string_view subsystem) const;
    const SubsystemType* subsystem_type(std::string_view type) const;
    CommandRef command(std::string_view subsystem, std::string_view name) const;
    bool has_type(std::string_view type) const;
    std::vector<std::string> subsystems_of_type(std::string_view type) const;
    // The index-th telemetry entry of a kind ("agent", ...), or nullptr.
    const TelemetrySpec* telemetry_of(std::string_view kind, std::size_t index = 0) const;
    std::size_t count_of(std::string_view kind) const;
};

}  // namespace rapid_runtime

#endif
