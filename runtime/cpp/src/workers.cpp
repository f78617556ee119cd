#include "rapid_runtime/workers.hpp"

#include <algorithm>

namespace rapid_runtime {

void Workers::spawn(std::function<void()> job) {
    std::lock_guard<std::mutex> lock(mutex_);
    reap();
    std::uint64_t number = next_++;
    // The job says it finished as its very last step: a finished thread only has to
    // return, so joining it under the lock is short.
    slots_.push_back({number, std::thread([this, number, job = std::move(job)] {
                          try {
                              job();
                          } catch (...) {  // the jobs catch their own; a thread must never terminate the bridge
                          }
                          std::lock_guard<std::mutex> done(mutex_);
                          finished_.push_back(number);
                      })});
}

void Workers::reap() {
    for (std::uint64_t number : finished_) {
        auto it = std::find_if(slots_.begin(), slots_.end(), [number](const Slot& s) { return s.number == number; });
        if (it != slots_.end()) {  // (join_all may have taken it)
            it->thread.join();
            slots_.erase(it);
        }
    }
    finished_.clear();
}

void Workers::join_all() {
    for (;;) {
        std::list<Slot> taken;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            reap();
            if (slots_.empty()) return;
            taken.splice(taken.end(), slots_);
        }
        for (auto& s : taken) s.thread.join();  // outside the lock: each needs it to finish
        // (their numbers, still listed as finished, are dropped by the next reap)
    }
}

std::size_t Workers::running() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return slots_.size() - finished_.size();
}

}  // namespace rapid_runtime
