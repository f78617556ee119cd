// Handlers of the Stale test asset (tests/cpp_runtime/test_stale_telemetry.py): a position
// source that can die. A feeder thread republishes the last pose at 10 Hz stamped with the
// time the source last measured it (as a bridge fed by another process does: the ROS 2
// bridge); Feed/cut stops the source (its measurement time freezes: the kill -9 of issue 39),
// Feed/resume brings it back. The agent state goes out once, at start (no rate: not watched).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include <rapid_runtime/dds/messages.hpp>
#include <rapid_runtime/dds/telemetry.hpp>

#include "handlers.hpp"

namespace rapid_stale::bridge {

namespace {

class Source {
public:
    void start(::rapid_runtime::dds::Bridge& b) {
        ::rapid_runtime::dds::Telemetry(b).agent_state({});
        thread_ = std::thread([this, &b] { run(b); });
    }
    void stop() {
        {
            std::lock_guard<std::mutex> lock(m_);
            stopping_ = true;
        }
        wake_.notify_all();
        if (thread_.joinable()) thread_.join();
    }
    std::atomic<bool> alive{true};

private:
    void run(::rapid_runtime::dds::Bridge& b) {
        std::int64_t measured = ::rapid_runtime::dds::now_us();
        double x = 0;
        for (;;) {
            {
                std::unique_lock<std::mutex> lock(m_);
                if (wake_.wait_for(lock, std::chrono::milliseconds(100), [this] { return stopping_; })) return;
            }
            if (alive) {
                measured = ::rapid_runtime::dds::now_us();
                x += 0.1;
            }
            ::rapid_runtime::dds::Telemetry(b).position({x, 0, 0}, {0, 0, 0, 1}, {}, {}, {}, 0, measured);
        }
    }
    std::thread thread_;
    std::mutex m_;
    std::condition_variable wake_;
    bool stopping_ = false;
};

class Feed final : public FeedHandler {
public:
    explicit Feed(Source& s) : s_(s) {}
    ::rapid_runtime::Result cut([[maybe_unused]] ::rapid_runtime::CommandContext& ctx) override {
        s_.alive = false;
        return ::rapid_runtime::Result::ok("source cut");
    }
    ::rapid_runtime::Result resume([[maybe_unused]] ::rapid_runtime::CommandContext& ctx) override {
        s_.alive = true;
        return ::rapid_runtime::Result::ok("source back");
    }

private:
    Source& s_;
};

}  // namespace

HandlerSet make_handlers() {
    static Source source;  // (outlives the handlers; its thread joined in on_stop)
    HandlerSet set;
    set.feed = ::std::make_unique<Feed>(source);
    set.on_start = [](::rapid_runtime::dds::Bridge& b) { source.start(b); };
    set.on_stop = [] { source.stop(); };
    return set;
}

}  // namespace rapid_stale::bridge
