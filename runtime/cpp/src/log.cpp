#include "rapid_runtime/log.hpp"

#include <chrono>

#include "rapid_runtime/text.hpp"

namespace rapid_runtime {

Log::Log(std::function<void(const std::string&)> write, std::size_t rate, std::function<double()> clock)
    : write_(std::move(write)), rate_(rate), clock_(std::move(clock)) {
    if (!clock_)
        clock_ = [] {
            return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
        };
    window_ = clock_();
}

void Log::operator()(const std::string& text) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        double now = clock_();
        if (now - window_ >= 1.0) {
            if (left_out_ != 0) write_("(" + std::to_string(left_out_) + " log lines left out in the last second)");
            window_ = now;
            lines_ = 0;
            left_out_ = 0;
        }
        if (++lines_ > rate_) {
            ++left_out_;
            return;
        }
    }
    write_(visible(text, 1000));
}

}  // namespace rapid_runtime
