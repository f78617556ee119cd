// One command the manager accepted: its state between intake and its final ack.
#ifndef RAPID_RUNTIME_RUN_HPP
#define RAPID_RUNTIME_RUN_HPP

#include <memory>

#include "command.hpp"
#include "handlers.hpp"
#include "tables.hpp"
#include "vocabulary.hpp"

namespace rapid_runtime {

struct Run {
    std::shared_ptr<const Cmd> cmd;
    CommandRef ref;
    bool queued = false;  // came through the queue (not BYPASS)
    std::shared_ptr<CommandContext> ctx;  // set when it starts
    bool requeue = false;  // preempted: back to the queue's front when its handler returns
    bool done = false;
    RecordStatus record_status = RecordStatus::Inline;

    const std::string& id() const { return cmd->cmd_id; }
    bool abortable() const { return ref.spec != nullptr && ref.spec->abortable; }
};

using RunPtr = std::shared_ptr<Run>;

}  // namespace rapid_runtime

#endif
