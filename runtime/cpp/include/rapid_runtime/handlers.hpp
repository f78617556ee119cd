// What an asset's handlers see: the command's context, the result, the failures.
//
// Handlers::execute(ctx) runs on a thread of its own and may run long:
// - return Result::ok(text): COMPLETED/OK (text is Ack.message);
// - return Result::failed(why) or throw CommandFailed(why): COMPLETED/EXEC_FAILED;
// - notice ctx.cancelled() (DELETE, cancelAll, stopAllMotion, a preempting command) and
//   return (anything) or throw Cancelled: COMPLETED/CANCELED, or REQUEUED when it was
//   preempted and will run again;
// - any other exception: EXEC_FAILED "handler error: ...", and the bridge keeps running.
// ctx.progress(text) sends an EXECUTING ack carrying text. Generated glue (phase 2)
// implements execute() by unpacking ctx.args() into typed per-command methods.
#ifndef RAPID_RUNTIME_HANDLERS_HPP
#define RAPID_RUNTIME_HANDLERS_HPP

#include <atomic>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "command.hpp"
#include "tables.hpp"
#include "vocabulary.hpp"

namespace rapid_runtime {

class CommandFailed : public std::runtime_error {
public:
    explicit CommandFailed(const std::string& why) : std::runtime_error(why) {}
};

class Cancelled : public std::exception {
public:
    const char* what() const noexcept override { return "canceled"; }
};

struct Result {
    Completion completion = Completion::Ok;
    std::string message;

    static Result ok(std::string text = {}) { return {Completion::Ok, std::move(text)}; }
    static Result failed(std::string why) { return {Completion::ExecFailed, std::move(why)}; }
    static Result canceled() { return {Completion::Canceled, "canceled"}; }
};

class CommandContext {
public:
    CommandContext(std::shared_ptr<const Cmd> cmd, CommandRef ref, std::function<void(const std::string&)> progress)
        : cmd_(std::move(cmd)), ref_(ref), progress_(std::move(progress)) {}

    const Cmd& cmd() const { return *cmd_; }
    const CommandSpec& spec() const { return *ref_.spec; }
    const std::string& type() const { return ref_.type->name; }  // the subsystem type (Arm)
    const std::string& command() const { return ref_.spec->name; }
    const std::string& subsystem() const { return cmd_->subsystem; }  // the instance (LeftArm)
    const std::string& source() const { return cmd_->cmd_src; }
    const std::vector<Value>& args() const { return cmd_->args; }
    // The i-th argument as its DataType's C++ type (validated before the handler runs).
    template <class T>
    const T& arg(std::size_t i) const { return std::get<T>(cmd_->args.at(i)); }

    // An EXECUTING ack carrying text (cut to 127 bytes); nothing once the command is done.
    void progress(const std::string& text) { progress_(text); }
    bool cancelled() const { return cancelled_.load(); }
    // Wait, waking early on cancellation; true when not cancelled.
    bool sleep(double seconds);
    // Throw Cancelled if the command was cancelled.
    void check() const {
        if (cancelled()) throw Cancelled();
    }
    // The runtime's: cancel (wakes sleep()).
    void cancel();

private:
    std::shared_ptr<const Cmd> cmd_;
    CommandRef ref_;
    std::function<void(const std::string&)> progress_;
    std::atomic<bool> cancelled_{false};
    std::mutex mutex_;
    std::condition_variable wake_;
};

// Base of the (generated, user-owned) handlers. A command no handler serves answers
// EXEC_FAILED "not implemented".
class Handlers {
public:
    virtual ~Handlers() = default;
    virtual Result execute(CommandContext& ctx);
};

}  // namespace rapid_runtime

#endif
