"""The lines of test code the stream tests put in the generated handlers.cpp (harness.py):
(headers, code ahead of make_handlers(), code inside it), as a robot team would write them."""
from __future__ import annotations

# Robonaut 2 consumes X-Arm-2's hand pose: the typed callback counts samples and keeps the
# last x; every state change prints both (the test reads the bridge's stdout).
R2 = ("#include <atomic>\n#include <cstdio>\n", """
namespace {

::std::atomic<long> got{0};
::std::atomic<double> last_x{0.0};

class CountingStreams final : public Streams {
public:
    void handPose(const ::rapid::PositionSample& sample) override {
        got.fetch_add(1, ::std::memory_order_relaxed);
        last_x.store(sample.pose.xyz[0], ::std::memory_order_relaxed);
    }
    void on_state(const ::rapid_runtime::StreamSpec& stream, ::rapid_runtime::StreamState state) override {
        ::std::printf("stream %s %s after %ld samples, last x %.0f\\n", stream.name.c_str(),
                      ::rapid_runtime::state_name(state), got.load(), last_x.load());
        ::std::fflush(stdout);
    }
};

}  // namespace
""", """    set.streams = ::std::make_unique<CountingStreams>();
""")

# X-Arm-2 writes its hand pose at the stream's rate from a thread of its own, x counting
# the samples (so the reader can tell it got the writer's latest).
XARM2 = ("#include <atomic>\n#include <thread>\n#include <time.h>\n", """
namespace {

::std::atomic<bool> writing{false};
::std::thread writer;

void write_hand_pose() {
    timespec next{};
    ::clock_gettime(CLOCK_MONOTONIC, &next);
    double n = 0;
    while (writing.load()) {
        next.tv_nsec += 2000000;  // 500 Hz
        if (next.tv_nsec >= 1000000000L) {
            next.tv_nsec -= 1000000000L;
            ++next.tv_sec;
        }
        ::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
        auto& s = handPose_sample();
        s.pose.xyz = {++n, 0.25, 1.0};
        send_handPose();
    }
}

}  // namespace
""", """    set.on_start = [](::rapid_runtime::dds::Bridge&) {
        writing = true;
        writer = ::std::thread(write_hand_pose);
    };
    set.on_stop = [] {
        writing = false;
        if (writer.joinable()) writer.join();
    };
""")

