// The Restarter test asset's handlers (tests/field/restart_asset.py's descriptor) for its C++
// bridge in tests/cpp_runtime/test_restart.py: Worker/work appends the cmdId to the file
// $RESTART_EXECFILE as it starts (one O_APPEND write: a kill -9 loses nothing written), so
// the test counts how often each command ran, then works for `ms` milliseconds.
#include <fcntl.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

#include "handlers.hpp"

namespace rapid_restarter::bridge {

namespace {

class Queue final : public QueueHandler {
public:
    ::rapid_runtime::Result loadMacro([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
                                      [[maybe_unused]] const ::std::string& name) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

class Worker final : public WorkerHandler {
public:
    Worker() {
        const char* path = std::getenv("RESTART_EXECFILE");
        fd_ = path != nullptr ? ::open(path, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644) : -1;
    }
    ~Worker() override {
        if (fd_ >= 0) ::close(fd_);
    }
    ::rapid_runtime::Result work(::rapid_runtime::CommandContext& ctx, ::std::int32_t ms) override {
        if (fd_ < 0) return ::rapid_runtime::Result::failed("RESTART_EXECFILE not set or not writable");
        std::string line = ctx.cmd().cmd_id + "\n";
        if (::write(fd_, line.data(), line.size()) != static_cast<ssize_t>(line.size()))
            return ::rapid_runtime::Result::failed("execution not recorded");
        if (!ctx.sleep(ms / 1000.0)) return ::rapid_runtime::Result::ok("interrupted");
        return ::rapid_runtime::Result::ok("worked");
    }

private:
    int fd_ = -1;
};

}  // namespace

HandlerSet make_handlers() {
    HandlerSet set;
    set.queue = ::std::make_unique<Queue>();
    set.worker = ::std::make_unique<Worker>();
    return set;
}

}  // namespace rapid_restarter::bridge
