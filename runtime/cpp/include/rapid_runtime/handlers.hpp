// What an asset's handlers see: the command's context, the result, the failures.
//
// Handlers::execute(ctx) runs on a thread of its own and may run long:
// - return Result::ok(text): COMPLETED/OK (text is Ack.message);
// - return Result::failed(why) or throw CommandFailed(why): COMPLETED/EXEC_FAILED;
// - notice ctx.cancelled() (DELETE, REPLACE, cancelAll, stopAllMotion, a preempting
//   command, shutdown) and return (anything) or throw Cancelled: COMPLETED/CANCELED, or
//   REQUEUED when it was preempted and will run again. A handler told to stop that has not
//   returned within its stop bound (CommandSpec::stop_timeout_ms, else the bridge's
//   --stop-timeout, 2000 ms) is answered EXEC_FAILED "handler did not stop" and leaves the
//   queue; what it returns later is ignored;
// - any other exception: EXEC_FAILED "handler error: ...", one log line, and the bridge
//   keeps running.
// ctx.progress(text) sends an EXECUTING ack carrying text. Generated glue (phase 2)
// implements execute() by unpacking ctx.args() into typed per-command methods.
//
// The context's lifetime (runtime/cpp/README.md, "The handler contract"): it is shared-owned.
// The handler call holds it; ctx.share() gives a thread of your own (a driver's callback)
// a std::shared_ptr that keeps it valid for as long as that thread holds it. The runtime
// also keeps the contexts of the last FINAL_ACKS_KEPT (1024) finished commands. Every call
// on a context after its command is done (final ack written) is a no-op or reads the
// final state: progress() does nothing, cancelled() stays as it was.
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
#include "texts.hpp"
#include "vocabulary.hpp"

namespace rapid_runtime {

class CommandFailed : public std::runtime_error {
public:
    explicit CommandFailed(const std::string& why) : std::runtime_error(why) {}
};

class Cancelled : public std::exception {
public:
    const char* what() const noexcept override { return texts::CANCELED; }
};

struct Result {
    Completion completion = Completion::Ok;
    std::string message;

    static Result ok(std::string text = {}) { return {Completion::Ok, std::move(text)}; }
    static Result failed(std::string why) { return {Completion::ExecFailed, std::move(why)}; }
    static Result canceled() { return {Completion::Canceled, texts::CANCELED}; }
    // What an unwritten handler answers (the generated stubs' Result::failed("not
    // implemented") is the same result): EXEC_FAILED "not implemented".
    static Result not_implemented() { return {Completion::ExecFailed, NOT_IMPLEMENTED}; }
    bool is_not_implemented() const { return completion == Completion::ExecFailed && message == NOT_IMPLEMENTED; }

    static constexpr const char* NOT_IMPLEMENTED = texts::NOT_IMPLEMENTED;
};

class CommandContext : public std::enable_shared_from_this<CommandContext> {
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

    // An EXECUTING ack carrying text (made valid UTF-8, cut to 127 bytes); from any thread;
    // nothing once the command is done.
    void progress(const std::string& text) {
        if (!closed_.load()) progress_(text);
    }
    // The context shared: keeps it valid for a thread that may call it after the handler
    // returned (a driver's callback). Only for a context the runtime made.
    std::shared_ptr<CommandContext> share() { return shared_from_this(); }
    // The command has its final ack (every call from now on is a no-op).
    bool done() const { return closed_.load(); }
    bool cancelled() const { return cancelled_.load(); }
    // Wait, waking early on cancellation; true when not cancelled.
    bool sleep(double seconds);
    // Throw Cancelled if the command was cancelled.
    void check() const {
        if (cancelled()) throw Cancelled();
    }
    // The runtime's: cancel (wakes sleep()); close once the command is done.
    void cancel();
    void close() { closed_.store(true); }

private:
    std::shared_ptr<const Cmd> cmd_;
    CommandRef ref_;
    std::function<void(const std::string&)> progress_;
    std::atomic<bool> cancelled_{false};
    std::atomic<bool> closed_{false};
    std::mutex mutex_;
    std::condition_variable wake_;
};

// Base of the (generated, user-owned) handlers. A command no handler serves answers
// EXEC_FAILED "not implemented" (Result::not_implemented()).
class Handlers {
public:
    virtual ~Handlers() = default;
    virtual Result execute(CommandContext& ctx);
};

}  // namespace rapid_runtime

#endif
