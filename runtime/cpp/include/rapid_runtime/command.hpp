// A received Command as plain data: what the protocol logic sees (the DDS layer builds it
// and, for QueueState records, turns it back into a rapid::Command).
#ifndef RAPID_RUNTIME_COMMAND_HPP
#define RAPID_RUNTIME_COMMAND_HPP

#include <cstdint>
#include <string>
#include <vector>

#include "value.hpp"
#include "vocabulary.hpp"

namespace rapid_runtime {

struct Cmd {
    std::string cmd_id;
    std::string cmd_src;
    std::string subsystem;
    std::string name;
    std::vector<Value> args;  // in the order sent; a Value's index is its union discriminator
    QueueAction action = QueueAction::Bypass;
    std::string target;  // targetCmdId
    std::string src_name;  // hdr.srcName: the commander
    std::string asset_name;  // hdr.assetName: the addressed asset
    std::int32_t serial = 0;
    std::int64_t stamp = 0;  // hdr.timeStamp as sent
    std::int32_t status_code = 0;  // hdr.statusCode as sent
};

}  // namespace rapid_runtime

#endif
