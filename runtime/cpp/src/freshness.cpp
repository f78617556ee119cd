#include "rapid_runtime/freshness.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "rapid_runtime/texts.hpp"

namespace rapid_runtime {

std::optional<double> stale_after_ms(const TelemetrySpec& e) {
    if (e.kind != "position" && e.kind != "joint" && e.kind != "agent" && e.kind != "image") return std::nullopt;
    if (e.stale_after_ms > 0) return e.stale_after_ms;
    if (e.rate && *e.rate > 0) return std::max(STALE_PERIODS * 1000.0 / *e.rate, STALE_FLOOR_MS);
    return std::nullopt;
}

std::string stale_name(const TelemetrySpec& e) {
    if (const TelemetryTopic* t = e.topic("sample")) return t->topic;
    if (const TelemetryTopic* t = e.topic("state")) return t->topic;
    return e.topics.empty() ? e.kind : e.topics.front().topic;
}

std::string silent_text(const std::string& name, double age_seconds) { return texts::source_silent(name, age_seconds); }

std::string back_text(const std::string& name) { return texts::source_back(name); }

Freshness::Freshness(Clock clock) : clock_(std::move(clock)) {
    if (!clock_)
        clock_ = [] {
            return std::chrono::duration_cast<std::chrono::microseconds>(
                       std::chrono::system_clock::now().time_since_epoch())
                .count();
        };
}

void Freshness::watch(const std::string& name, double bound_ms) {
    std::lock_guard<std::mutex> lock(mutex_);
    bounds_us_[name] = static_cast<std::int64_t>(std::llround(bound_ms * 1000.0));
}

bool Freshness::watched(const std::string& name) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return bounds_us_.count(name) > 0;
}

bool Freshness::empty() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return bounds_us_.empty();
}

double Freshness::smallest_bound_ms() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::int64_t least = 0;
    for (const auto& [name, bound] : bounds_us_) least = least == 0 ? bound : std::min(least, bound);
    return static_cast<double>(least) / 1000.0;
}

Freshness::Offer Freshness::offer(const std::string& name, std::int64_t stamp_us) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto bound = bounds_us_.find(name);
    if (bound == bounds_us_.end()) return {true, false};
    if (clock_() - stamp_us > bound->second) return {false, false};
    auto newest = newest_.find(name);
    if (newest == newest_.end()) newest_[name] = stamp_us;
    else newest->second = std::max(newest->second, stamp_us);
    bool back = silent_.erase(name) > 0;
    return {true, back};
}

std::vector<std::pair<std::string, double>> Freshness::check() {
    std::vector<std::pair<std::string, double>> out;
    std::lock_guard<std::mutex> lock(mutex_);
    const std::int64_t now = clock_();
    for (const auto& [name, newest] : newest_) {
        if (silent_.count(name) == 0 && now - newest > bounds_us_.at(name)) {
            silent_.insert(name);
            out.emplace_back(name, static_cast<double>(now - newest) / 1e6);
        }
    }
    return out;
}

std::vector<std::string> Freshness::silent_names() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return {silent_.begin(), silent_.end()};
}

}  // namespace rapid_runtime
