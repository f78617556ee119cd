#include "rapid_runtime/pending.hpp"

#include <algorithm>

namespace rapid_runtime {

RunPtr Pending::find(std::string_view cmd_id) const {
    for (const auto& r : items_)
        if (r->id() == cmd_id) return r;
    return nullptr;
}

bool Pending::contains(const RunPtr& run) const { return std::find(items_.begin(), items_.end(), run) != items_.end(); }

bool Pending::insert_after(std::string_view target, RunPtr run) {
    if (target == HEAD) {
        items_.push_front(std::move(run));
        return true;
    }
    for (auto it = items_.begin(); it != items_.end(); ++it) {
        if ((*it)->id() == target) {
            items_.insert(it + 1, std::move(run));
            return true;
        }
    }
    return false;
}

RunPtr Pending::replace(std::string_view target, RunPtr run) {
    for (auto& r : items_) {
        if (r->id() == target) {
            RunPtr old = std::move(r);
            r = std::move(run);
            return old;
        }
    }
    return nullptr;
}

void Pending::remove(const RunPtr& run) {
    auto it = std::find(items_.begin(), items_.end(), run);
    if (it != items_.end()) items_.erase(it);
}

RunPtr Pending::pop_ready(const std::function<bool(const std::string&)>& busy) {
    if (items_.empty() || busy(items_.front()->cmd->subsystem)) return nullptr;
    RunPtr run = std::move(items_.front());
    items_.pop_front();
    return run;
}

}  // namespace rapid_runtime
