// The Faulty test asset's handlers (tests/cpp_runtime/test_handler_faults.py's descriptor):
// user code on a bad day, one fault per command, for its C++ bridge run live (issue 42).
//   Worker/helper    hands its context to a thread of its own (by reference and shared) and
//                    returns; that thread reports progress after the command is done, then
//                    writes $FAULTY_DIR/helper-<cmdId> (the test waits for it)
//   Worker/stubborn  writes $FAULTY_DIR/started-<cmdId>, then ignores cancel: runs until
//                    $FAULTY_DIR/release exists
//   Worker/quick     answers at once
//   Worker/badText   answers with invalid UTF-8 and a NUL, and publishes a TextMessage
//                    carrying the same (the asset's text telemetry entry)
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include <rapid_runtime/dds/telemetry.hpp>

#include "handlers.hpp"

namespace rapid_faulty::bridge {

namespace {

const std::string BAD_TEXT = std::string("bad \xff\xfe text \xe2\x82 nul[") + '\0' + "] end";

std::string in_dir(const std::string& name) {
    const char* dir = std::getenv("FAULTY_DIR");
    return std::string(dir != nullptr ? dir : ".") + "/" + name;
}

void touch(const std::string& name) { std::ofstream(in_dir(name)) << "1\n"; }

bool exists(const std::string& name) { return static_cast<bool>(std::ifstream(in_dir(name))); }

class Queue final : public QueueHandler {
public:
    ::rapid_runtime::Result loadMacro([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
                                      [[maybe_unused]] const ::std::string& name) override {
        return ::rapid_runtime::Result::not_implemented();
    }
};

class Worker final : public WorkerHandler {
public:
    ::rapid_runtime::Result helper(::rapid_runtime::CommandContext& ctx) override {
        ::rapid_runtime::CommandContext* raw = &ctx;  // a driver callback that kept a reference
        std::shared_ptr<::rapid_runtime::CommandContext> shared = ctx.share();
        std::string id = ctx.cmd().cmd_id;
        std::thread([raw, shared, id] {
            std::this_thread::sleep_for(std::chrono::milliseconds(300));
            raw->progress("late progress (by reference)");
            std::this_thread::sleep_for(std::chrono::milliseconds(300));
            shared->progress("late progress (shared)");
            touch("helper-" + id);
        }).detach();
        return ::rapid_runtime::Result::ok("helper started");
    }

    ::rapid_runtime::Result stubborn(::rapid_runtime::CommandContext& ctx) override {
        touch("started-" + ctx.cmd().cmd_id);
        while (!exists("release")) std::this_thread::sleep_for(std::chrono::milliseconds(10));  // never looks at cancel
        return ::rapid_runtime::Result::ok("released");
    }

    ::rapid_runtime::Result quick([[maybe_unused]] ::rapid_runtime::CommandContext& ctx) override {
        return ::rapid_runtime::Result::ok("quick");
    }

    ::rapid_runtime::Result badText([[maybe_unused]] ::rapid_runtime::CommandContext& ctx) override {
        if (auto* b = bridge.load()) ::rapid_runtime::dds::Telemetry(*b).text(BAD_TEXT, "faults\xc3");
        return ::rapid_runtime::Result::ok(BAD_TEXT);
    }

    std::atomic<::rapid_runtime::dds::Bridge*> bridge{nullptr};  // (set when the bridge has started)
};

}  // namespace

HandlerSet make_handlers() {
    HandlerSet set;
    set.queue = ::std::make_unique<Queue>();
    auto worker = ::std::make_unique<Worker>();
    Worker* w = worker.get();
    set.worker = ::std::move(worker);
    set.on_start = [w](::rapid_runtime::dds::Bridge& b) { w->bridge = &b; };
    return set;
}

}  // namespace rapid_faulty::bridge
