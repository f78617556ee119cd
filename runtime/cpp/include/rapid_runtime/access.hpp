// Who may command the asset. Two independent gates (docs/runtime.md):
// - the descriptor's allow-list: which cmdSrc may send which Subsystem/command;
// - the controller (assets with an AccessControl subsystem): only the source holding
//   control may command, except AccessControl's own commands and the asset itself.
// Mobility/stopAllMotion passes both: stopping is always allowed.
#ifndef RAPID_RUNTIME_ACCESS_HPP
#define RAPID_RUNTIME_ACCESS_HPP

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tables.hpp"

namespace rapid_runtime {

inline constexpr std::size_t MAX_REQUESTORS = 16;  // AccessControlState.requestors: String32Sequence16

bool always_allowed(std::string_view subsystem_type, std::string_view command);
// The allow-list's answer; no access_control section allows every source.
bool allowed(const std::optional<AccessSpec>& spec, std::string_view source, std::string_view subsystem,
             std::string_view command);

// The controller and the queue of requestors. Each operation returns what happened (a
// note, for Ack.message) or why it failed (EXEC_FAILED).
class Control {
public:
    struct Outcome {
        bool ok = true;
        std::string text;  // the note when ok, else the reason
    };

    bool holds(std::string_view source) const { return !controller_.empty() && source == controller_; }
    Outcome request(const std::string& source);
    Outcome grab(const std::string& source);
    Outcome release(const std::string& source);
    Outcome transfer(const std::string& source, const std::string& new_controller);

    const std::string& controller() const { return controller_; }  // "" : none
    const std::vector<std::string>& requestors() const { return requestors_; }

private:
    void give(const std::string& source);
    std::string controller_;
    std::vector<std::string> requestors_;
};

}  // namespace rapid_runtime

#endif
