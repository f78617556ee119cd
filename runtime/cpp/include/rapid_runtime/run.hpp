// One command the manager accepted: its state between intake and its final ack.
#ifndef RAPID_RUNTIME_RUN_HPP
#define RAPID_RUNTIME_RUN_HPP

#include <chrono>
#include <memory>
#include <vector>

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
    bool handling = false;  // its handler was called and has not returned
    bool stopping = false;  // told to stop; answered "handler did not stop" at stop_by
    std::chrono::steady_clock::time_point stop_by{};
    std::vector<std::weak_ptr<Run>> stopped;  // stopAllMotion: the Mobility commands it told to stop
    std::vector<std::shared_ptr<CommandContext>> past;  // contexts of earlier runs (preempted, requeued)

    const std::string& id() const { return cmd->cmd_id; }
    bool abortable() const { return ref.spec != nullptr && ref.spec->abortable; }
};

using RunPtr = std::shared_ptr<Run>;

}  // namespace rapid_runtime

#endif
