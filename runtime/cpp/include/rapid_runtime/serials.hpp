// Config serials: `serial` is the start time in seconds, and a config whose content changes
// gets a new one, always larger than the last (receivers ignore a config whose serial did
// not change). Samples copy their config's serial. Content is compared as bytes (the DDS
// layer passes the config's encoding with its header cleared).
#ifndef RAPID_RUNTIME_SERIALS_HPP
#define RAPID_RUNTIME_SERIALS_HPP

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>

#include "rapid_runtime/journal.hpp"

namespace rapid_runtime {

class Serials {
public:
    // start: the first serial (default: now, in seconds since the epoch). now: seconds (tests).
    // issued(serial): told of every serial given out, the start one first (the restart
    // journal records the highest, so a restarted bridge's serials are larger).
    explicit Serials(std::int64_t start = -1, std::function<std::int64_t()> now = {},
                     std::function<void(std::int32_t)> issued = {});

    std::int32_t start() const { return start_; }
    // The serial of the topic's config (the start serial before it was set).
    std::int32_t of(const std::string& topic) const;
    // (serial, changed): a new serial only when content differs from the last one.
    std::pair<std::int32_t, bool> update(const std::string& topic, const std::string& content);

private:
    std::function<std::int64_t()> now_;
    std::function<void(std::int32_t)> issued_;
    std::int32_t start_;
    std::int32_t last_;
    std::map<std::string, std::pair<std::string, std::int32_t>> topics_;  // topic -> (content, serial)
};

// The configs' serials at a start, as every bridge chooses them: restart_serial's first
// serial (the start time when it is -1), each serial issued recorded in `journal` (none:
// nullptr), which gets the start record too.
Serials start_serials(std::int64_t requested, const JournalRecovered& recovered, Journal* journal, std::int64_t now);

}  // namespace rapid_runtime

#endif
