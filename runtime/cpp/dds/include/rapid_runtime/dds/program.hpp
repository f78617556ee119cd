// The bridge program a generated asset package's `main` runs (`<package>_bridge`): options,
// the Bridge on the asset's tables and built-in Fast DDS profiles, its configs, the user's
// handlers or the simulated robot, until Admin/shutdown, a signal or --seconds.
//
//   <package>_bridge [--simulate] [--sim-speed X] [--domain N] [--transport local|lan|wan]
//                    [--qos PROFILES_XML] [--seconds S] [--command-window N]
//                    [--journal DIR | --no-journal]
//
// Prints "bridge ready: asset A, domain D, partition P[, simulated]" once configs and states
// are out and commands are read, "bridge stopped" at the end. Exit status: 0, 2 for a
// usage error, 1 when the bridge cannot start (its reason on stderr).
#ifndef RAPID_RUNTIME_DDS_PROGRAM_HPP
#define RAPID_RUNTIME_DDS_PROGRAM_HPP

#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include <rapid_runtime/handlers.hpp>
#include <rapid_runtime/tables.hpp>

#include "bridge.hpp"
#include "bridge_handlers.hpp"
#include "simulate.hpp"

namespace rapid_runtime {
namespace dds {

struct Program {
    const Tables* tables = nullptr;
    std::string_view profiles_xml;  // the asset's generated Fast DDS profiles (built in)
    std::function<void(Bridge&)> publish_configs;  // the computed configs (asset.hpp)
    std::function<std::unique_ptr<BridgeHandlers>()> make_handlers;  // the user's
    std::vector<CustomPublisher> custom;  // extension telemetry the simulated robot publishes
    // --simulate: the asset's setpoint streams on the simulated robot (the generated glue's,
    // when the asset has streams: dds/stream.hpp SimulatedStreams), kept until the bridge stops.
    std::function<std::shared_ptr<void>(Bridge&, Simulator&)> simulated_streams;
};

int run_bridge(int argc, char** argv, const Program& program);

}  // namespace dds
}  // namespace rapid_runtime

#endif
