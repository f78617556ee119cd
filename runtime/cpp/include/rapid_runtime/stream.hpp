// Setpoint streams (docs/realtime.md): what one stream is (the descriptor's `streams:`
// entry as the generated code states it) and its state machine, without DDS, so the
// rules are tested without a network. Header-only: the DDS layer and the logic tests
// include it, no build file lists it.
//
//   waiting --sample--> active --deadline missed / writer lost--> lost --sample--> active
//
// A sample with a NaN or an infinity (dds/stream.hpp finite_sample) is not a sample: it never
// reaches the handler, is counted (non_finite()), and does not keep the stream alive. DDS's
// own DEADLINE is met by any sample, so the monitor keeps the time of the last finite one and
// a non-finite sample that arrives after the deadline since then loses the stream as a
// missed deadline would (cause NonFinite) (its on_loss action is taken while the writer writes only NaN).
// The first non-finite sample of a run of them (after a finite one, or the first ever) is
// flagged so the reporting thread says so once per run, not once per sample.
//
// Counters are atomics: samples arrive on the middleware's receive thread, deadlines on its
// event thread, and the reporting thread reads them; nothing here allocates or locks.
#ifndef RAPID_RUNTIME_STREAM_HPP
#define RAPID_RUNTIME_STREAM_HPP

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

namespace rapid_runtime {

enum class LossAction { Stop, Hold, None };
enum class StreamState : int { Waiting = 0, Active = 1, Lost = 2 };
// What made an active stream lost: its DEADLINE passed without a sample, or its writer's
// LIVELINESS lapsed (the writer process is gone or frozen, or left the domain).
// NonFinite: samples kept coming past the deadline, but none finite (NaN or Inf: dropped).
enum class LossCause : int { Deadline = 0, Liveliness = 1, NonFinite = 2 };

inline const char* state_name(StreamState s) {
    switch (s) {
    case StreamState::Active: return "active";
    case StreamState::Lost: return "lost";
    default: return "waiting";
    }
}

inline const char* action_name(LossAction a) {
    switch (a) {
    case LossAction::Stop: return "stop";
    case LossAction::Hold: return "hold";
    default: return "none";
    }
}

struct StreamSpec {
    std::string name;
    bool input = true;
    std::string type;  // DDS type name (rapid::PositionSample)
    std::string topic;
    std::string partition;  // the writer's
    std::string profile;  // RapidStream_<name> of the asset's Fast DDS profiles
    double rate_hz = 0;
    double deadline_ms = 0;
    double liveliness_ms = 0;
    LossAction on_loss = LossAction::Stop;
    std::string subsystem;
    std::string state_key;  // agent value keys the runtime fills ("" none)
    std::string missed_key;
};

class StreamMonitor {
public:
    using Clock = std::chrono::steady_clock;

    // A valid sample arrived; true when the stream became active (first sample, recovery).
    bool sample(Clock::time_point now = Clock::now()) {
        samples_.fetch_add(1, std::memory_order_relaxed);
        last_finite_.store(now.time_since_epoch().count(), std::memory_order_relaxed);
        in_run_.store(false, std::memory_order_relaxed);
        return set(StreamState::Active, LossCause::Deadline);
    }
    // A sample with a NaN or an infinity arrived (dropped, not handed to anyone). Counted;
    // when the stream is active and no finite sample came within `deadline_ms`, it is lost
    // as a missed deadline (one more missed). lost: the stream was just lost; first_of_run:
    // this sample begins a run of non-finite ones (worth one report).
    struct NonFinite {
        bool lost = false;
        bool first_of_run = false;
    };
    NonFinite non_finite_sample(double deadline_ms, Clock::time_point now = Clock::now()) {
        NonFinite out;
        non_finite_.fetch_add(1, std::memory_order_relaxed);
        out.first_of_run = !in_run_.exchange(true, std::memory_order_relaxed);
        if (out.first_of_run) runs_.fetch_add(1, std::memory_order_relaxed);
        auto last = Clock::time_point(Clock::duration(last_finite_.load(std::memory_order_relaxed)));
        if (deadline_ms > 0 && now - last > std::chrono::duration<double, std::milli>(deadline_ms) &&
            state() == StreamState::Active) {
            missed_.fetch_add(1, std::memory_order_relaxed);
            out.lost = lose(LossCause::NonFinite);
        }
        return out;
    }
    // The reader's DEADLINE passed without a sample (total_count_change of them); true when
    // the stream was active and is now lost.
    bool deadline_missed(std::uint64_t count = 1) {
        missed_.fetch_add(count, std::memory_order_relaxed);
        return lose(LossCause::Deadline);
    }
    // LIVELINESS: alive writers now; true when the stream was active and is now lost, or
    // when the last writer just went (reported even when a deadline lost the stream first).
    bool writers_alive(int alive) {
        int was = alive_.exchange(alive, std::memory_order_acq_rel);
        if (alive > 0 || was <= 0) return false;
        gone_.fetch_add(1, std::memory_order_relaxed);
        lose(LossCause::Liveliness);
        return true;
    }

    StreamState state() const { return static_cast<StreamState>(state_.load(std::memory_order_acquire) & STATE); }
    // Why the stream was last lost (meaningful while state() is Lost).
    LossCause cause() const { return static_cast<LossCause>(state_.load(std::memory_order_acquire) >> CAUSE_SHIFT); }
    std::uint64_t samples() const { return samples_.load(std::memory_order_relaxed); }
    // Samples dropped for a NaN or an infinity (never handed to the handler).
    std::uint64_t non_finite() const { return non_finite_.load(std::memory_order_relaxed); }
    // Runs of non-finite samples begun (see non_finite_sample): the reporting thread's cue.
    std::uint64_t non_finite_runs() const { return runs_.load(std::memory_order_relaxed); }
    std::uint64_t missed() const { return missed_.load(std::memory_order_relaxed); }
    std::uint64_t losses() const { return losses_.load(std::memory_order_relaxed); }
    // Times the last alive writer went (LIVELINESS lapsed or the writer left).
    std::uint64_t writers_gone() const { return gone_.load(std::memory_order_relaxed); }

private:
    // The state and the cause of a loss in one atomic: the reporting thread never reads a
    // "lost" with the cause of an earlier loss.
    static constexpr int STATE = 0xf;
    static constexpr int CAUSE_SHIFT = 4;

    bool lose(LossCause cause) {
        int expected = static_cast<int>(StreamState::Active);
        if (!state_.compare_exchange_strong(expected, pack(StreamState::Lost, cause), std::memory_order_acq_rel))
            return false;
        losses_.fetch_add(1, std::memory_order_relaxed);
        return true;
    }
    bool set(StreamState s, LossCause cause) {
        int old = state_.exchange(pack(s, cause), std::memory_order_acq_rel);
        return (old & STATE) != static_cast<int>(s);
    }
    static int pack(StreamState s, LossCause c) { return static_cast<int>(s) | (static_cast<int>(c) << CAUSE_SHIFT); }

    std::atomic<int> state_{static_cast<int>(StreamState::Waiting)};
    std::atomic<int> alive_{0};
    std::atomic<std::uint64_t> samples_{0};
    std::atomic<std::uint64_t> missed_{0};
    std::atomic<std::uint64_t> losses_{0};
    std::atomic<std::uint64_t> gone_{0};
    std::atomic<std::uint64_t> non_finite_{0};
    std::atomic<std::uint64_t> runs_{0};
    std::atomic<bool> in_run_{false};
    std::atomic<Clock::rep> last_finite_{0};
};

}  // namespace rapid_runtime

#endif
