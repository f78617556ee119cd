// The door between the command reader and the manager: a flood from one participant must
// neither grow the bridge without bound nor lock an operator out
// (runtime/rapid_runtime/intake.py is the reference).
//
//     Intake intake(manager, log);   intake.start();   // a worker thread runs the manager
//     intake.offer(cmd, writer);     // the reader thread: every decoded Command, never blocks
//                                    // (but see the last point)
//
// - One FIFO per writer (the DDS writer the sample came from), served round-robin.
// - Control commands go first: a writer whose next command is a control command is served
//   before the others; a writer's own commands keep their order.
// - Each writer holds at most per_writer commands waiting; past that its commands are
//   answered COMPLETED/EXEC_FAILED "bridge busy" without running. Those answers wait in a
//   bounded list (shed_answers); when that is full too, commands are dropped unanswered,
//   counted and logged once per writer.
// - A command the sink answers at once (CommandSink::answers_at_once: the runtime's own
//   BYPASS echo, noOp, AccessControl, without a journal) is handed to the sink on the
//   offering thread when nothing waits and no batch is with the sink: the same order, one
//   thread handoff less. offer() then takes as long as that answer (the acks written).
#ifndef RAPID_RUNTIME_INTAKE_HPP
#define RAPID_RUNTIME_INTAKE_HPP

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <list>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "command.hpp"
#include "manager.hpp"

namespace rapid_runtime {

inline constexpr std::size_t PER_WRITER = 256;  // commands of one writer waiting for the manager
inline constexpr std::size_t MAX_WRITERS = 256;  // writers with a FIFO of their own; past that they share one
inline constexpr std::size_t SHED_ANSWERS = 4096;  // "busy" answers waiting to be written
inline constexpr const char* SHARED_WRITER = "";  // the FIFO of writers past MAX_WRITERS
inline constexpr std::size_t BATCH = 32;  // commands handed to the manager at once (one journal sync)

std::string busy_message(std::size_t per_writer);

class Intake {
public:
    Intake(CommandSink& sink, std::function<void(const std::string&)> log, std::size_t per_writer = PER_WRITER,
           std::size_t shed_answers = SHED_ANSWERS);
    ~Intake();  // stops
    Intake(const Intake&) = delete;
    Intake& operator=(const Intake&) = delete;

    void start();
    void stop();
    // writer: an id of the DDS writer (its GUID in hex).
    void offer(Cmd cmd, const std::string& writer);
    std::size_t waiting() const;
    std::size_t unanswered(const std::string& writer) const;
    std::size_t shed(const std::string& writer) const;

private:
    struct Next {
        Cmd cmd;
        bool shed;
    };
    using Fifos = std::list<std::pair<std::string, std::deque<Cmd>>>;
    bool next(std::unique_lock<std::mutex>& lock, Next& out);
    Fifos::iterator control_writer();
    void run();
    void hand_over(Next got);  // one command as a batch of its own
    void hand_over_one(Next& got);

    CommandSink& sink_;
    std::function<void(const std::string&)> log_;
    std::size_t per_writer_;
    std::size_t shed_limit_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    // The round: writers with commands waiting, the next to serve first.
    Fifos fifos_;
    std::map<std::string, Fifos::iterator> index_;
    std::deque<Cmd> shed_;
    std::map<std::string, std::size_t> unanswered_;
    std::map<std::string, std::size_t> shed_count_;
    bool stopping_ = false;
    bool shed_turn_ = false;
    bool working_ = false;  // a batch is with the sink (the worker's, or one handed over by offer())
    std::thread thread_;
};

}  // namespace rapid_runtime

#endif
