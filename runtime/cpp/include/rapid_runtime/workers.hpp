// Threads of running handlers: each command's handler runs on a thread of its own (it may
// run long); finished threads are joined when the next one starts, and all of them when
// the owner goes (a handler that ignores cancellation holds that up: it is the handler's).
#ifndef RAPID_RUNTIME_WORKERS_HPP
#define RAPID_RUNTIME_WORKERS_HPP

#include <cstdint>
#include <functional>
#include <list>
#include <mutex>
#include <thread>
#include <vector>

namespace rapid_runtime {

class Workers {
public:
    Workers() = default;
    Workers(const Workers&) = delete;
    Workers& operator=(const Workers&) = delete;
    ~Workers() { join_all(); }

    void spawn(std::function<void()> job);
    void join_all();
    std::size_t running() const;

private:
    struct Slot {
        std::uint64_t number;
        std::thread thread;
    };
    void reap();  // under the lock
    mutable std::mutex mutex_;
    std::list<Slot> slots_;
    std::vector<std::uint64_t> finished_;  // numbers of threads whose job returned
    std::uint64_t next_ = 0;
};

}  // namespace rapid_runtime

#endif
