// generated from runtime/spec/texts.yaml; do not edit (python -m rapidgen.protocol_texts)
//! Every reason and ack text the runtime writes: runtime/spec/texts.yaml's words, one constant
//! or function per text (the Python runtime's texts.py and the C++ runtime's texts.hpp come from
//! the same table). A text with placeholders is a function taking them in the table's `args`
//! order: `text` a &str (a name from the wire shortened by the caller), `count` a usize,
//! `seconds` an f64 written with one decimal.

/// BAD_SYNTAX: a command whose cmdId is empty
pub const EMPTY_CMD_ID: &str = "empty cmdId";

/// BAD_SYNTAX: a QueueAction outside the enumeration (Python: its value as decoded; C++: its number)
pub fn unknown_queue_action(action: &str) -> String {
    format!("unknown queue action {action}")
}

/// BAD_SYNTAX: a queue action other than QUEUE_BYPASS to an asset without a Queue subsystem
pub fn no_queue(action: &str) -> String {
    format!("{action} refused: this asset has no command queue (send QUEUE_BYPASS)")
}

/// BAD_SYNTAX: QUEUE_BYPASS or QUEUE_APPEND with a targetCmdId
pub fn target_not_taken(action: &str, target: &str) -> String {
    format!("{action} takes no targetCmdId (got '{target}')")
}

/// BAD_SYNTAX: QUEUE_INSERT, QUEUE_REPLACE or QUEUE_DELETE without a targetCmdId
pub fn target_needed(action: &str) -> String {
    format!("{action} needs a targetCmdId")
}

/// BAD_SYNTAX: QUEUE_INSERT after a command neither pending nor running (nor 'head')
pub fn unknown_insert_target(target: &str) -> String {
    format!("unknown targetCmdId '{target}' (pending ids, the running one or 'head')")
}

/// BAD_SYNTAX: QUEUE_REPLACE or QUEUE_DELETE of a command neither pending nor running
pub fn unknown_target(target: &str) -> String {
    format!("unknown targetCmdId '{target}' (not pending or running)")
}

/// EXEC_FAILED: QUEUE_APPEND or QUEUE_INSERT with the queue at its limit
pub fn queue_full(limit: usize) -> String {
    format!("queue full ({limit} pending); retry later")
}

/// EXEC_FAILED: QUEUE_BYPASS with the bypass limit's commands running
pub fn bypass_full(limit: usize) -> String {
    format!("{limit} commands already running beside the queue; retry later")
}

/// EXEC_FAILED: QUEUE_REPLACE or QUEUE_DELETE of a running command that is not abortable
pub fn target_not_abortable(target: &str) -> String {
    format!("target '{target}' is running and not abortable")
}

/// EXEC_FAILED: a command arriving while the bridge stops; CANCELED: each pending command at shutdown
pub const ASSET_SHUTTING_DOWN: &str = "asset shutting down";

/// BAD_SYNTAX: a subsystem the asset does not have
pub fn unknown_subsystem(subsystem: &str) -> String {
    format!("unknown subsystem '{subsystem}'")
}

/// BAD_SYNTAX: a command the subsystem's type does not have
pub fn unknown_command(command: &str, subsystem: &str) -> String {
    format!("unknown command '{command}' for subsystem '{subsystem}'")
}

/// BAD_SYNTAX: a command of one parameter sent with another number of arguments
pub fn argument_count_one(command: &str, got: usize) -> String {
    format!("{command} takes 1 argument, got {got}")
}

/// BAD_SYNTAX: a command of 0 or several parameters sent with another number of arguments
pub fn argument_count(command: &str, count: usize, got: usize) -> String {
    format!("{command} takes {count} arguments, got {got}")
}

/// BAD_SYNTAX: an argument whose DataType is not its parameter's (index from 1, DataType names)
pub fn argument_type(index: usize, name: &str, expected: &str, got: &str) -> String {
    format!("argument {index} ({name}) must be {expected}, got {got}")
}

/// BAD_SYNTAX: an argument outside its parameter's shape, range or allowed values (why: one of the three below)
pub fn argument_invalid(index: usize, name: &str, why: &str) -> String {
    format!("argument {index} ({name}): {why}")
}

/// argument_invalid's why: a RAPID_STRING longer than its String128 carries
pub fn string_too_long(size: usize, limit: usize) -> String {
    format!("{size} bytes (max {limit})")
}

/// argument_invalid's why: a value outside the allowed values (value as Python's repr, allowed '|'-separated)
pub fn not_one_of(value: &str, allowed: &str) -> String {
    format!("{value} not one of {allowed}")
}

/// argument_invalid's why: a number (or a vector's element) outside min..max (Python's {:g}; -inf/inf for an open end)
pub fn out_of_range(value: &str, low: &str, high: &str) -> String {
    format!("{value} not in [{low}, {high}]")
}

/// BAD_SYNTAX: the descriptor's allow-list does not let this cmdSrc send this command
pub fn access_not_allowed(source: &str, subsystem: &str, command: &str) -> String {
    format!("RAPID access violation: {source} may not send {subsystem}/{command}")
}

/// BAD_SYNTAX: a command from a source that does not hold control (assets with AccessControl)
pub fn access_no_control(source: &str) -> String {
    format!("RAPID access violation: {source} does not have control (send requestControl)")
}

/// OK: requestControl with no controller (or from the controller)
pub fn control_granted(source: &str) -> String {
    format!("control granted to {source}")
}

/// OK: requestControl from a source already waiting
pub fn request_already_queued(controller: &str) -> String {
    format!("request already queued; {controller} has control")
}

/// EXEC_FAILED: requestControl with AccessControlState.requestors full
pub fn requests_full(limit: usize) -> String {
    format!("{limit} requests already queued")
}

/// OK: requestControl while another source has control
pub fn request_queued(controller: &str) -> String {
    format!("request queued; {controller} has control")
}

/// OK: grabControl from another source than the controller
pub fn control_taken_from(before: &str) -> String {
    format!("control taken from {before}")
}

/// OK: grabControl with no controller (or from the controller)
pub const CONTROL_TAKEN: &str = "control taken";

/// EXEC_FAILED: releaseControl or transferControl from a source that does not hold control
pub fn no_control(source: &str) -> String {
    format!("{source} does not have control")
}

/// OK: releaseControl, control passing to the first requestor
pub fn control_released_to(controller: &str) -> String {
    format!("control released to {controller}")
}

/// OK: releaseControl with no requestor waiting
pub const CONTROL_RELEASED: &str = "control released";

/// EXEC_FAILED: transferControl to an empty (or blank) name
pub const NEW_CONTROLLER_EMPTY: &str = "newController is empty";

/// EXEC_FAILED: transferControl to a name AccessControlState's String32 cannot hold
pub const NEW_CONTROLLER_TOO_LONG: &str = "newController longer than 31 bytes";

/// OK: transferControl
pub fn control_transferred(controller: &str) -> String {
    format!("control transferred to {controller}")
}

/// CANCELED: a pending command a QUEUE_REPLACE took the place of (the replacing cmdId)
pub fn replaced_by(cmd_id: &str) -> String {
    format!("replaced by {cmd_id}")
}

/// CANCELED: a pending command a QUEUE_DELETE removed (the deleting cmdId)
pub fn deleted_by(cmd_id: &str) -> String {
    format!("deleted by {cmd_id}")
}

/// OK: the QUEUE_DELETE of a pending command
pub fn target_canceled(target: &str) -> String {
    format!("{target} canceled")
}

/// OK: the QUEUE_DELETE of a running abortable command (its own final ack follows)
pub fn cancel_requested(target: &str) -> String {
    format!("{target} cancel requested; handler has not stopped yet")
}

/// REQUEUED: a suspendable queued command a QUEUE_BYPASS command on its subsystem stopped
pub const PREEMPTED: &str = "preempted; back in the queue";

/// CANCELED: each pending command Queue/cancelAll removed
pub const CANCELED_BY_CANCEL_ALL: &str = "cancelAll";

/// CANCELED: each pending Mobility command Mobility/stopAllMotion removed
pub const CANCELED_BY_STOP_ALL_MOTION: &str = "stopAllMotion";

/// OK: Queue/cancelAll with abortable commands running (joined to the next by '; ')
pub fn handlers_asked_to_stop(count: usize) -> String {
    format!("{count} handler(s) asked to stop, not stopped yet")
}

/// OK: Queue/cancelAll with commands running that are not abortable
pub fn non_abortable_running(count: usize) -> String {
    format!("{count} non-abortable command(s) still running")
}

/// OK (or the handler's completion): Mobility/stopAllMotion completing while canceled motion handlers still run, after the message and '; '
pub fn motion_not_stopped(count: usize) -> String {
    format!("{count} motion handler(s) not stopped yet")
}

/// OK: Mobility/stopAllMotion whose handler is the generated stub (or missing)
pub const NO_HARDWARE_STOP: &str = "motion commands canceled; no hardware stop handler";

/// OK: Admin/shutdown
pub const SHUTTING_DOWN: &str = "shutting down";

/// CANCELED: a handler that returned after being told to stop, or raised Cancelled
pub const CANCELED: &str = "canceled";

/// EXEC_FAILED: a handler that failed without saying why
pub const FAILED: &str = "failed";

/// EXEC_FAILED: a command whose handler is the generated stub, or missing
pub const NOT_IMPLEMENTED: &str = "not implemented";

/// EXEC_FAILED: a handler that raised an unexpected exception (its type's name and text)
pub fn handler_error(error_type: &str, message: &str) -> String {
    format!("handler error: {error_type}: {message}")
}

/// EXEC_FAILED: a C++ handler that threw something not a std::exception (a Python exception always has a type) (only the cpp runtime)
pub const HANDLER_ERROR_UNKNOWN: &str = "handler error: unknown exception";

/// EXEC_FAILED: a C++ handler whose Result says ACK_COMPLETED_NOT (a Python handler cannot return one) (only the cpp runtime)
pub const NO_COMPLETION: &str = "handler gave no completion";

/// EXEC_FAILED: a handler still running at its stop bound, or at the shutdown bound
pub const DID_NOT_STOP: &str = "handler did not stop";

/// CANCELED: a command the journal shows accepted and not started when the asset went down
pub const RESTARTED_QUEUED: &str = "asset restarted before it ran";

/// EXEC_FAILED: a command the journal shows running when the asset went down
pub const RESTARTED_RUNNING: &str = "asset restarted while it ran; outcome unknown";

/// EXEC_FAILED: a command shed at the door, its writer's queue full (not run, its cmdId not remembered)
pub fn bridge_busy(count: usize) -> String {
    format!("bridge busy: {count} commands from this writer already waiting; retry later")
}

/// TextMessage MSG_WARN: a watched telemetry entry's source silent past its bound
pub fn source_silent(entry: &str, age: f64) -> String {
    format!("{entry} source silent for {age:.1} s: samples stopped")
}

/// TextMessage MSG_INFO: a silent entry's first current sample
pub fn source_back(entry: &str) -> String {
    format!("{entry} source back")
}
