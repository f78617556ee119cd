// The pending queue: ordered runs, with the positions INSERT, REPLACE and DELETE name.
#ifndef RAPID_RUNTIME_PENDING_HPP
#define RAPID_RUNTIME_PENDING_HPP

#include <deque>
#include <functional>
#include <string_view>

#include "run.hpp"

namespace rapid_runtime {

class Pending {
public:
    std::size_t size() const { return items_.size(); }
    bool empty() const { return items_.empty(); }
    const std::deque<RunPtr>& items() const { return items_; }  // front first

    RunPtr find(std::string_view cmd_id) const;
    bool contains(const RunPtr& run) const;
    void append(RunPtr run) { items_.push_back(std::move(run)); }
    void push_front(RunPtr run) { items_.push_front(std::move(run)); }
    // After the pending command `target`; at the front for "head". False: target not pending.
    bool insert_after(std::string_view target, RunPtr run);
    // Put run where target is; returns the removed target, or null.
    RunPtr replace(std::string_view target, RunPtr run);
    void remove(const RunPtr& run);
    // The front run, removed, unless busy(its subsystem) (a bypass command preempted it):
    // the queue runs in order, so nothing behind it starts either.
    RunPtr pop_ready(const std::function<bool(const std::string&)>& busy);

private:
    std::deque<RunPtr> items_;
};

}  // namespace rapid_runtime

#endif
