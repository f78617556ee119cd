// The bridge's log: one visible line per call (wire text escaped), at most `rate` lines a
// second, then how many were left out (a flood of bad commands must not become a flood
// of log lines).
#ifndef RAPID_RUNTIME_LOG_HPP
#define RAPID_RUNTIME_LOG_HPP

#include <cstddef>
#include <functional>
#include <mutex>
#include <string>

namespace rapid_runtime {

inline constexpr std::size_t LOG_RATE = 50;

class Log {
public:
    // write: where lines go (stderr in the bridge); clock: seconds, monotonic.
    explicit Log(std::function<void(const std::string&)> write, std::size_t rate = LOG_RATE,
                 std::function<double()> clock = {});
    void operator()(const std::string& text);

private:
    std::function<void(const std::string&)> write_;
    std::size_t rate_;
    std::function<double()> clock_;
    std::mutex mutex_;
    double window_;
    std::size_t lines_ = 0;
    std::size_t left_out_ = 0;
};

}  // namespace rapid_runtime

#endif
