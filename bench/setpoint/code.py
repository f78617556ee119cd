"""The bench's lines in the two generated handlers.cpp (tests/streams/harness.py puts them
there): Pilot64 writes a 64-joint JointSample at 1 kHz from a thread of its own, Arm64's
typed callback records each sample's arrival; both count heap allocations on their thread
(alloc_count.cpp) and write their records to a file when the bridge stops."""
from __future__ import annotations

HEAD = """#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

#include <pthread.h>
#include <sched.h>
#include <time.h>

extern "C" unsigned long rapid_bench_thread_allocs();
"""

COMMON = """
namespace {

::std::int64_t ns_of(clockid_t clock) {
    timespec t{};
    ::clock_gettime(clock, &t);
    return static_cast<::std::int64_t>(t.tv_sec) * 1000000000LL + t.tv_nsec;
}

::std::size_t samples_wanted() {
    const char* n = ::std::getenv("SETPOINT_SAMPLES");
    return n != nullptr ? static_cast<::std::size_t>(::std::strtoul(n, nullptr, 10)) : 10000u;
}

bool realtime_priority() {  // SCHED_FIFO when the machine grants it (not needed to run)
    sched_param p{};
    p.sched_priority = 80;
    return ::pthread_setschedparam(::pthread_self(), SCHED_FIFO, &p) == 0;
}

struct Record {
    ::std::int64_t mono_ns;  // arrival (reader) or wake-up (writer), CLOCK_MONOTONIC
    ::std::int64_t real_ns;  // arrival, CLOCK_REALTIME (reader)
    ::std::int64_t sent_us;  // hdr.timeStamp (reader)
    unsigned long allocs;  // this thread's allocations so far
    ::std::int64_t seq;  // hdr.serial: the writer's sample number
};
::std::vector<Record> records;
::std::atomic<::std::size_t> recorded{0};
::std::atomic<int> rt_granted{-1};

void dump(const char* env) {
    const char* path = ::std::getenv(env);
    if (path == nullptr) return;
    ::std::FILE* f = ::std::fopen(path, "w");
    if (f == nullptr) return;
    ::std::fprintf(f, "rt %d\\n", rt_granted.load());
    for (::std::size_t i = 0; i < recorded.load(); ++i)
        ::std::fprintf(f, "%lld %lld %lld %lu %lld\\n", static_cast<long long>(records[i].mono_ns),
                       static_cast<long long>(records[i].real_ns), static_cast<long long>(records[i].sent_us),
                       records[i].allocs, static_cast<long long>(records[i].seq));
    ::std::fclose(f);
}
"""

ARM = (HEAD, COMMON + """
class BenchStreams final : public Streams {
public:
    void setpoints(const ::rapid::JointSample& sample) override {
        ::std::size_t i = recorded.load(::std::memory_order_relaxed);
        if (i == 0) rt_granted = realtime_priority() ? 1 : 0;  // the receive thread
        if (i >= records.size()) return;
        records[i] = {ns_of(CLOCK_MONOTONIC), ns_of(CLOCK_REALTIME), sample.hdr.timeStamp, rapid_bench_thread_allocs(),
                      sample.hdr.serial};
        recorded.store(i + 1, ::std::memory_order_release);
    }
};

}  // namespace
""", """    records.resize(samples_wanted() + 1000);  // up front: recording allocates nothing
    set.streams = ::std::make_unique<BenchStreams>();
    set.on_stop = [] { dump("SETPOINT_READER_OUT"); };
""")

PILOT = (HEAD, COMMON + """
::std::atomic<bool> writing{false};
::std::thread writer;

void write_setpoints() {
    rt_granted = realtime_priority() ? 1 : 0;
    auto& s = setpoints_sample();
    s.anglePos.assign(64, 0.0f);  // 64 joints: sized once, rewritten in place
    s.angleVel.assign(64, 0.0f);
    s.torque.assign(64, 0.0f);
    timespec next{};
    ::clock_gettime(CLOCK_MONOTONIC, &next);
    for (::std::size_t i = 0; writing.load(::std::memory_order_relaxed); ++i) {  // until the bridge stops
        next.tv_nsec += 1000000;  // 1 kHz
        if (next.tv_nsec >= 1000000000L) {
            next.tv_nsec -= 1000000000L;
            ++next.tv_sec;
        }
        ::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
        ::std::int64_t woke = ns_of(CLOCK_MONOTONIC);
        for (::std::size_t j = 0; j < 64; ++j) s.anglePos[j] = static_cast<float>(i % 1000) * 1e-3f + static_cast<float>(j);
        s.hdr.serial = static_cast<::std::int32_t>(i);
        send_setpoints();
        if (i < records.size()) {
            records[i] = {woke, static_cast<::std::int64_t>(next.tv_sec) * 1000000000LL + next.tv_nsec, 0,
                          rapid_bench_thread_allocs(), static_cast<::std::int64_t>(i)};
            recorded.store(i + 1, ::std::memory_order_release);
        }
    }
}

}  // namespace
""", """    records.resize(samples_wanted() + 5000);  // the reader's window starts after discovery
    set.on_start = [](::rapid_runtime::dds::Bridge&) {
        writing = true;
        writer = ::std::thread(write_setpoints);
    };
    set.on_stop = [] {
        writing = false;
        if (writer.joinable()) writer.join();
        dump("SETPOINT_WRITER_OUT");
    };
""")
