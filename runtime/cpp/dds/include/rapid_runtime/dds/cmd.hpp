// rapid_cmd: the ground-side client (client.hpp) as a program, rapidgen cmd's twin in C++.
//
//   rapid_cmd [options] SUBSYSTEM COMMAND [key=value ...]
//
// Arguments by parameter name, checked against the asset's dictionary (the live
// CommandConfig, merged with the built-in tables' limits and defaults; the tables alone
// when none comes within --discover), defaults filled; waits for the asset, sends once,
// prints the acks as `rapidgen cmd` does until the final COMPLETED:
//
//   K10Red <- Mobility/simpleMove frame='SITE' xyt=1,2,0  [cmdId ID, QUEUE_APPEND, from rapid_cmd]
//     QUEUED
//     EXECUTING
//     COMPLETED OK
//
// Exit 0 on COMPLETED/OK, 1 otherwise (an error, no ack, no asset), 2 for a usage error.
// --repeat N and --flood N are the benchmark's loops (bench/cpp_bridge.py): one JSON line.
// CMake: rapid_runtime_cpp_add_cmd(<target> PACKAGE <pkg> [BRIDGE_DIR <dir>]) builds it,
// with the generated bridge's tables and built-in profiles when BRIDGE_DIR is given.
#ifndef RAPID_RUNTIME_DDS_CMD_HPP
#define RAPID_RUNTIME_DDS_CMD_HPP

#include <string_view>

#include <rapid_runtime/tables.hpp>

namespace rapid_runtime {
namespace dds {

struct CmdProgram {
    const Tables* tables = nullptr;  // the asset's (a generated bridge's tables()), or none
    std::string_view profiles_xml;  // its built-in Fast DDS profiles, or none (--qos, FASTDDS_DEFAULT_PROFILES_FILE)
};

int run_cmd(int argc, char** argv, const CmdProgram& program);

}  // namespace dds
}  // namespace rapid_runtime

#endif
