// Plain data (command.hpp, value.hpp) <-> the asset package's ::rapid types. The DDS layer
// is compiled with one asset package (rapid_runtime_cpp_add_dds): every package declares
// the same ::rapid types, so this is written once.
#ifndef RAPID_RUNTIME_DDS_MESSAGES_HPP
#define RAPID_RUNTIME_DDS_MESSAGES_HPP

#include <cstdint>
#include <string>
#include <vector>

#include "rapid_runtime_dds_types.hpp"
#include <rapid_runtime/command.hpp>
#include <rapid_runtime/manager.hpp>

namespace rapid_runtime {
namespace dds {

// Header.timeStamp: microseconds since 1970-01-01 UTC.
std::int64_t now_us();
::rapid::Header header(const std::string& src, const std::string& asset, std::int32_t serial, std::int32_t status = 0);

Value value_of(const ::rapid::ParameterUnion& u);
::rapid::ParameterUnion union_of(const Value& v);

// A received rapid::Command as plain data, and back (QueueState records, the ground side).
Cmd command_in(const ::rapid::Command& c);
::rapid::Command command_out(const Cmd& c);

// The Ack copies the command's header (soraCore: srcName is the commander), timestamp refreshed.
void fill_ack(::rapid::Ack& ack, const Cmd& cmd, AckStatus status, Completion completed, const std::string& message);

::rapid::QueueState queue_state(const ::rapid::Header& hdr, const std::vector<Record>& pending,
                                const std::vector<Record>& active, const std::vector<Record>& completed);

}  // namespace dds
}  // namespace rapid_runtime

#endif
