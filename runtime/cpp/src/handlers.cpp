#include "rapid_runtime/handlers.hpp"

#include <chrono>

namespace rapid_runtime {

bool CommandContext::sleep(double seconds) {
    std::unique_lock<std::mutex> lock(mutex_);
    auto span = std::chrono::duration<double>(seconds > 0 ? seconds : 0.0);
    return !wake_.wait_for(lock, span, [this] { return cancelled_.load(); });
}

void CommandContext::cancel() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        cancelled_.store(true);
    }
    wake_.notify_all();
}

Result Handlers::execute(CommandContext&) { return Result::not_implemented(); }

}  // namespace rapid_runtime
