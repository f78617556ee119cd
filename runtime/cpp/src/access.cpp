#include "rapid_runtime/access.hpp"

#include <algorithm>

#include "rapid_runtime/texts.hpp"

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
        return {true, texts::control_granted(source)};
    }
    if (std::find(requestors_.begin(), requestors_.end(), source) != requestors_.end())
        return {true, texts::request_already_queued(controller_)};
    if (requestors_.size() >= MAX_REQUESTORS) return {false, texts::requests_full(static_cast<long long>(MAX_REQUESTORS))};
    requestors_.push_back(source);
    return {true, texts::request_queued(controller_)};
}

Control::Outcome Control::grab(const std::string& source) {
    std::string before = controller_;
    give(source);
    return {true, !before.empty() && before != source ? texts::control_taken_from(before) : texts::CONTROL_TAKEN};
}

Control::Outcome Control::release(const std::string& source) {
    if (!holds(source)) return {false, texts::no_control(source)};
    std::string next;
    if (!requestors_.empty()) {
        next = requestors_.front();
        requestors_.erase(requestors_.begin());
    }
    controller_ = next;
    return {true, next.empty() ? texts::CONTROL_RELEASED : texts::control_released_to(next)};
}

Control::Outcome Control::transfer(const std::string& source, const std::string& new_controller) {
    if (!holds(source)) return {false, texts::no_control(source)};
    if (blank(new_controller)) return {false, texts::NEW_CONTROLLER_EMPTY};
    if (new_controller.size() > 31) return {false, texts::NEW_CONTROLLER_TOO_LONG};
    give(new_controller);
    return {true, texts::control_transferred(new_controller)};
}

void Control::give(const std::string& source) {
    controller_ = source;
    requestors_.erase(std::remove(requestors_.begin(), requestors_.end(), source), requestors_.end());
}

}  // namespace rapid_runtime
