// Stale telemetry (docs/runtime.md, "Stale telemetry"; the C++ twin of the Python runtime's
// rapid_runtime.telemetry.Freshness): telemetry never claims a freshness it does not have.
//
// A position, joint, agent or image entry has a stale bound: its descriptor's stale_after_ms,
// else STALE_PERIODS periods of its rate but at least STALE_FLOOR_MS; an entry with neither
// (published on change), text and custom entries are not watched. Per watched entry (by name:
// its sample topic, an agent's state topic) Freshness keeps the bound and the newest source
// time of a sample let out: a sample older than its entry's bound is refused; an entry whose
// newest source time is older than its bound is silent until a current sample comes. Times in
// microseconds since the epoch (the samples' stamps), from a clock that tests replace.
// No DDS here: dds/telemetry.hpp says it (log, TextMessage, the agent's stale_telemetry key).
#ifndef RAPID_RUNTIME_FRESHNESS_HPP
#define RAPID_RUNTIME_FRESHNESS_HPP

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "tables.hpp"

namespace rapid_runtime {

inline constexpr double STALE_PERIODS = 3;
inline constexpr double STALE_FLOOR_MS = 1000.0;
// The agent value key the runtime fills with the silent entries' names (", "-separated; ""
// when every watched source is current), when the agent entry declares it as RAPID_STRING.
inline constexpr const char* STALE_KEY = "stale_telemetry";

// The entry's stale bound in ms; none: not watched (a kind other than position, joint, agent
// and image, or neither stale_after_ms nor a rate).
std::optional<double> stale_after_ms(const TelemetrySpec& entry);

// An entry as the stale messages name it: its sample topic (an agent's state topic).
std::string stale_name(const TelemetrySpec& entry);

// What is said, word for word as the Python runtime says it.
std::string silent_text(const std::string& name, double age_seconds);  // "<name> source silent for 2.3 s: samples stopped"
std::string back_text(const std::string& name);                          // "<name> source back"

class Freshness {
public:
    using Clock = std::function<std::int64_t()>;  // microseconds since the epoch

    explicit Freshness(Clock clock = {});  // default: the wall clock

    void watch(const std::string& name, double bound_ms);
    bool watched(const std::string& name) const;
    bool empty() const;
    double smallest_bound_ms() const;  // 0 when nothing is watched

    struct Offer {
        bool ok;    // the sample may go out (false: older than its entry's bound)
        bool back;  // its entry was silent and is back with it
    };
    // A sample of that source time on that entry; unwatched entries always may.
    Offer offer(const std::string& name, std::int64_t stamp_us);

    // (name, seconds since its newest source time) of each entry newly silent since the last
    // check; an entry that never had a sample is not silent.
    std::vector<std::pair<std::string, double>> check();

    std::vector<std::string> silent_names() const;  // sorted

private:
    Clock clock_;
    mutable std::mutex mutex_;
    std::map<std::string, std::int64_t> bounds_us_;
    std::map<std::string, std::int64_t> newest_;
    std::set<std::string> silent_;
};

}  // namespace rapid_runtime

#endif
