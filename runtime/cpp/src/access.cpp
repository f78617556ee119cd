#include "rapid_runtime/access.hpp"

#include <algorithm>

namespace rapid_runtime {
namespace {

bool matches(std::string_view pattern, std::string_view subsystem, std::string_view command) {
    if (pattern == "*") return true;
    auto slash = pattern.find('/');
    std::string_view sub = pattern.substr(0, slash);
    std::string_view cmd = slash == std::string_view::npos ? std::string_view() : pattern.substr(slash + 1);
    return (sub == "*" || sub == subsystem) && (cmd == "*" || cmd == command);
}

bool blank(const std::string& s) {
    return std::all_of(s.begin(), s.end(), [](char c) { return c == ' ' || (c >= '\t' && c <= '\r'); });
}

}  // namespace

bool always_allowed(std::string_view subsystem_type, std::string_view command) {
    return subsystem_type == "Mobility" && command == "stopAllMotion";
}

bool allowed(const std::optional<AccessSpec>& spec, std::string_view source, std::string_view subsystem,
             std::string_view command) {
    if (!spec) return true;
    bool named = false;
    for (const auto& rule : spec->rules) {
        if (rule.source != source) continue;
        named = true;
        for (const auto& pattern : rule.allow)
            if (matches(pattern, subsystem, command)) return true;
    }
    return named ? false : spec->allow_by_default;
}

Control::Outcome Control::request(const std::string& source) {
    if (controller_.empty() || controller_ == source) {
        give(source);
        return {true, "control granted to " + source};
    }
    if (std::find(requestors_.begin(), requestors_.end(), source) != requestors_.end())
        return {true, "request already queued; " + controller_ + " has control"};
    if (requestors_.size() >= MAX_REQUESTORS) return {false, std::to_string(MAX_REQUESTORS) + " requests already queued"};
    requestors_.push_back(source);
    return {true, "request queued; " + controller_ + " has control"};
}

Control::Outcome Control::grab(const std::string& source) {
    std::string before = controller_;
    give(source);
    return {true, !before.empty() && before != source ? "control taken from " + before : "control taken"};
}

Control::Outcome Control::release(const std::string& source) {
    if (!holds(source)) return {false, source + " does not have control"};
    std::string next;
    if (!requestors_.empty()) {
        next = requestors_.front();
        requestors_.erase(requestors_.begin());
    }
    controller_ = next;
    return {true, next.empty() ? "control released" : "control released to " + next};
}

Control::Outcome Control::transfer(const std::string& source, const std::string& new_controller) {
    if (!holds(source)) return {false, source + " does not have control"};
    if (blank(new_controller)) return {false, "newController is empty"};
    if (new_controller.size() > 31) return {false, "newController longer than 31 bytes"};
    give(new_controller);
    return {true, "control transferred to " + new_controller};
}

void Control::give(const std::string& source) {
    controller_ = source;
    requestors_.erase(std::remove(requestors_.begin(), requestors_.end(), source), requestors_.end());
}

}  // namespace rapid_runtime
