#include "rapid_runtime/serials.hpp"

#include <algorithm>
#include <chrono>

namespace rapid_runtime {

Serials::Serials(std::int64_t start, std::function<std::int64_t()> now, std::function<void(std::int32_t)> issued)
    : now_(std::move(now)), issued_(std::move(issued)) {
    if (!now_)
        now_ = [] {
            return std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch())
                .count();
        };
    start_ = static_cast<std::int32_t>(start < 0 ? now_() : start);  // Header.serial is a long (32 bits)
    last_ = start_;
    if (issued_) issued_(start_);
}

std::int32_t Serials::of(const std::string& topic) const {
    auto it = topics_.find(topic);
    return it == topics_.end() ? start_ : it->second.second;
}

std::pair<std::int32_t, bool> Serials::update(const std::string& topic, const std::string& content) {
    auto it = topics_.find(topic);
    if (it != topics_.end()) {
        if (it->second.first == content) return {it->second.second, false};
        last_ = std::max<std::int32_t>(last_ + 1, static_cast<std::int32_t>(now_()));
    }
    topics_[topic] = {content, last_};
    if (issued_) issued_(last_);
    return {last_, true};
}

Serials start_serials(std::int64_t requested, const JournalRecovered& recovered, Journal* journal, std::int64_t now) {
    std::function<void(std::int32_t)> issued;
    if (journal != nullptr) issued = [journal](std::int32_t s) { journal->serial(s); };
    Serials serials(restart_serial(requested, recovered, now), {}, std::move(issued));
    if (journal != nullptr) journal->start(serials.start());
    return serials;
}

}  // namespace rapid_runtime
