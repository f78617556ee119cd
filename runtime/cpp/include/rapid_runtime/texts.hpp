// generated from runtime/spec/texts.yaml; do not edit (python -m rapidgen.protocol_texts)
// The reason and ack texts the runtime writes (runtime/spec/texts.yaml): one constant or
// function per text, the same words as the Python runtime's rapid_runtime/texts.py.
#ifndef RAPID_RUNTIME_TEXTS_HPP
#define RAPID_RUNTIME_TEXTS_HPP

#include <cstdio>
#include <string>

namespace rapid_runtime::texts {

namespace detail {
// Python's format(x, '.1f')
inline std::string one_decimal(double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.1f", x);
    return buf;
}
}  // namespace detail

// BAD_SYNTAX: a command whose cmdId is empty
inline constexpr const char* EMPTY_CMD_ID = "empty cmdId";
// BAD_SYNTAX: a QueueAction outside the enumeration (Python: its value as decoded; C++: its number)
inline std::string unknown_queue_action(const std::string& action) { return std::string("unknown queue action ") + action; }
// BAD_SYNTAX: a queue action other than QUEUE_BYPASS to an asset without a Queue subsystem
inline std::string no_queue(const std::string& action) { return action + " refused: this asset has no command queue (send QUEUE_BYPASS)"; }
// BAD_SYNTAX: QUEUE_BYPASS or QUEUE_APPEND with a targetCmdId
inline std::string target_not_taken(const std::string& action, const std::string& target) { return action + " takes no targetCmdId (got '" + target + "')"; }
// BAD_SYNTAX: QUEUE_INSERT, QUEUE_REPLACE or QUEUE_DELETE without a targetCmdId
inline std::string target_needed(const std::string& action) { return action + " needs a targetCmdId"; }
// BAD_SYNTAX: QUEUE_INSERT after a command neither pending nor running (nor 'head')
inline std::string unknown_insert_target(const std::string& target) { return std::string("unknown targetCmdId '") + target + "' (pending ids, the running one or 'head')"; }
// BAD_SYNTAX: QUEUE_REPLACE or QUEUE_DELETE of a command neither pending nor running
inline std::string unknown_target(const std::string& target) { return std::string("unknown targetCmdId '") + target + "' (not pending or running)"; }
// EXEC_FAILED: QUEUE_APPEND or QUEUE_INSERT with the queue at its limit
inline std::string queue_full(long long limit) { return std::string("queue full (") + std::to_string(limit) + " pending); retry later"; }
// EXEC_FAILED: QUEUE_BYPASS with the bypass limit's commands running
inline std::string bypass_full(long long limit) { return std::to_string(limit) + " commands already running beside the queue; retry later"; }
// EXEC_FAILED: QUEUE_REPLACE or QUEUE_DELETE of a running command that is not abortable
inline std::string target_not_abortable(const std::string& target) { return std::string("target '") + target + "' is running and not abortable"; }
// EXEC_FAILED: a command arriving while the bridge stops; CANCELED: each pending command at shutdown
inline constexpr const char* ASSET_SHUTTING_DOWN = "asset shutting down";
// BAD_SYNTAX: a subsystem the asset does not have
inline std::string unknown_subsystem(const std::string& subsystem) { return std::string("unknown subsystem '") + subsystem + "'"; }
// BAD_SYNTAX: a command the subsystem's type does not have
inline std::string unknown_command(const std::string& command, const std::string& subsystem) { return std::string("unknown command '") + command + "' for subsystem '" + subsystem + "'"; }
// BAD_SYNTAX: a command of one parameter sent with another number of arguments
inline std::string argument_count_one(const std::string& command, long long got) { return command + " takes 1 argument, got " + std::to_string(got); }
// BAD_SYNTAX: a command of 0 or several parameters sent with another number of arguments
inline std::string argument_count(const std::string& command, long long count, long long got) { return command + " takes " + std::to_string(count) + " arguments, got " + std::to_string(got); }
// BAD_SYNTAX: an argument whose DataType is not its parameter's (index from 1, DataType names)
inline std::string argument_type(long long index, const std::string& name, const std::string& expected, const std::string& got) { return std::string("argument ") + std::to_string(index) + " (" + name + ") must be " + expected + ", got " + got; }
// BAD_SYNTAX: an argument outside its parameter's shape, range or allowed values (why: one of the three below)
inline std::string argument_invalid(long long index, const std::string& name, const std::string& why) { return std::string("argument ") + std::to_string(index) + " (" + name + "): " + why; }
// argument_invalid's why: a RAPID_STRING longer than its String128 carries
inline std::string string_too_long(long long size, long long limit) { return std::to_string(size) + " bytes (max " + std::to_string(limit) + ")"; }
// argument_invalid's why: a value outside the allowed values (value as Python's repr, allowed '|'-separated)
inline std::string not_one_of(const std::string& value, const std::string& allowed) { return value + " not one of " + allowed; }
// argument_invalid's why: a number (or a vector's element) outside min..max (Python's {:g}; -inf/inf for an open end)
inline std::string out_of_range(const std::string& value, const std::string& low, const std::string& high) { return value + " not in [" + low + ", " + high + "]"; }
// BAD_SYNTAX: the descriptor's allow-list does not let this cmdSrc send this command
inline std::string access_not_allowed(const std::string& source, const std::string& subsystem, const std::string& command) { return std::string("RAPID access violation: ") + source + " may not send " + subsystem + "/" + command; }
// BAD_SYNTAX: a command from a source that does not hold control (assets with AccessControl)
inline std::string access_no_control(const std::string& source) { return std::string("RAPID access violation: ") + source + " does not have control (send requestControl)"; }
// OK: requestControl with no controller (or from the controller)
inline std::string control_granted(const std::string& source) { return std::string("control granted to ") + source; }
// OK: requestControl from a source already waiting
inline std::string request_already_queued(const std::string& controller) { return std::string("request already queued; ") + controller + " has control"; }
// EXEC_FAILED: requestControl with AccessControlState.requestors full
inline std::string requests_full(long long limit) { return std::to_string(limit) + " requests already queued"; }
// OK: requestControl while another source has control
inline std::string request_queued(const std::string& controller) { return std::string("request queued; ") + controller + " has control"; }
// OK: grabControl from another source than the controller
inline std::string control_taken_from(const std::string& before) { return std::string("control taken from ") + before; }
// OK: grabControl with no controller (or from the controller)
inline constexpr const char* CONTROL_TAKEN = "control taken";
// EXEC_FAILED: releaseControl or transferControl from a source that does not hold control
inline std::string no_control(const std::string& source) { return source + " does not have control"; }
// OK: releaseControl, control passing to the first requestor
inline std::string control_released_to(const std::string& controller) { return std::string("control released to ") + controller; }
// OK: releaseControl with no requestor waiting
inline constexpr const char* CONTROL_RELEASED = "control released";
// EXEC_FAILED: transferControl to an empty (or blank) name
inline constexpr const char* NEW_CONTROLLER_EMPTY = "newController is empty";
// EXEC_FAILED: transferControl to a name AccessControlState's String32 cannot hold
inline constexpr const char* NEW_CONTROLLER_TOO_LONG = "newController longer than 31 bytes";
// OK: transferControl
inline std::string control_transferred(const std::string& controller) { return std::string("control transferred to ") + controller; }
// CANCELED: a pending command a QUEUE_REPLACE took the place of (the replacing cmdId)
inline std::string replaced_by(const std::string& cmd_id) { return std::string("replaced by ") + cmd_id; }
// CANCELED: a pending command a QUEUE_DELETE removed (the deleting cmdId)
inline std::string deleted_by(const std::string& cmd_id) { return std::string("deleted by ") + cmd_id; }
// OK: the QUEUE_DELETE of a pending command
inline std::string target_canceled(const std::string& target) { return target + " canceled"; }
// OK: the QUEUE_DELETE of a running abortable command (its own final ack follows)
inline std::string cancel_requested(const std::string& target) { return target + " cancel requested; handler has not stopped yet"; }
// REQUEUED: a suspendable queued command a QUEUE_BYPASS command on its subsystem stopped
inline constexpr const char* PREEMPTED = "preempted; back in the queue";
// CANCELED: each pending command Queue/cancelAll removed
inline constexpr const char* CANCELED_BY_CANCEL_ALL = "cancelAll";
// CANCELED: each pending Mobility command Mobility/stopAllMotion removed
inline constexpr const char* CANCELED_BY_STOP_ALL_MOTION = "stopAllMotion";
// OK: Queue/cancelAll with abortable commands running (joined to the next by '; ')
inline std::string handlers_asked_to_stop(long long count) { return std::to_string(count) + " handler(s) asked to stop, not stopped yet"; }
// OK: Queue/cancelAll with commands running that are not abortable
inline std::string non_abortable_running(long long count) { return std::to_string(count) + " non-abortable command(s) still running"; }
// OK (or the handler's completion): Mobility/stopAllMotion completing while canceled motion handlers still run, after the message and '; '
inline std::string motion_not_stopped(long long count) { return std::to_string(count) + " motion handler(s) not stopped yet"; }
// OK: Mobility/stopAllMotion whose handler is the generated stub (or missing)
inline constexpr const char* NO_HARDWARE_STOP = "motion commands canceled; no hardware stop handler";
// OK: Admin/shutdown
inline constexpr const char* SHUTTING_DOWN = "shutting down";
// CANCELED: a handler that returned after being told to stop, or raised Cancelled
inline constexpr const char* CANCELED = "canceled";
// EXEC_FAILED: a handler that failed without saying why
inline constexpr const char* FAILED = "failed";
// EXEC_FAILED: a command whose handler is the generated stub, or missing
inline constexpr const char* NOT_IMPLEMENTED = "not implemented";
// EXEC_FAILED: a handler that raised an unexpected exception (its type's name and text)
inline std::string handler_error(const std::string& error_type, const std::string& message) { return std::string("handler error: ") + error_type + ": " + message; }
// EXEC_FAILED: a C++ handler that threw something not a std::exception (a Python exception always has a type) (only the cpp runtime)
inline constexpr const char* HANDLER_ERROR_UNKNOWN = "handler error: unknown exception";
// EXEC_FAILED: a C++ handler whose Result says ACK_COMPLETED_NOT (a Python handler cannot return one) (only the cpp runtime)
inline constexpr const char* NO_COMPLETION = "handler gave no completion";
// EXEC_FAILED: a handler still running at its stop bound, or at the shutdown bound
inline constexpr const char* DID_NOT_STOP = "handler did not stop";
// CANCELED: a command the journal shows accepted and not started when the asset went down
inline constexpr const char* RESTARTED_QUEUED = "asset restarted before it ran";
// EXEC_FAILED: a command the journal shows running when the asset went down
inline constexpr const char* RESTARTED_RUNNING = "asset restarted while it ran; outcome unknown";
// EXEC_FAILED: a command shed at the door, its writer's queue full (not run, its cmdId not remembered)
inline std::string bridge_busy(long long count) { return std::string("bridge busy: ") + std::to_string(count) + " commands from this writer already waiting; retry later"; }
// TextMessage MSG_WARN: a watched telemetry entry's source silent past its bound
inline std::string source_silent(const std::string& entry, double age) { return entry + " source silent for " + detail::one_decimal(age) + " s: samples stopped"; }
// TextMessage MSG_INFO: a silent entry's first current sample
inline std::string source_back(const std::string& entry) { return entry + " source back"; }

}  // namespace rapid_runtime::texts

#endif
