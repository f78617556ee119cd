# generated from runtime/spec/texts.yaml; do not edit (python -m rapidgen.protocol_texts)
"""The reason and ack texts the runtime writes (runtime/spec/texts.yaml): one constant
or function per text, the same words as the C++ runtime's rapid_runtime/texts.hpp."""
from __future__ import annotations

from typing import Final


# BAD_SYNTAX: a command whose cmdId is empty
EMPTY_CMD_ID: Final = 'empty cmdId'


def unknown_queue_action(action: str) -> str:
    # BAD_SYNTAX: a QueueAction outside the enumeration (Python: its value as decoded; C++: its number)
    return 'unknown queue action ' + action


def no_queue(action: str) -> str:
    # BAD_SYNTAX: a queue action other than QUEUE_BYPASS to an asset without a Queue subsystem
    return action + ' refused: this asset has no command queue (send QUEUE_BYPASS)'


def target_not_taken(action: str, target: str) -> str:
    # BAD_SYNTAX: QUEUE_BYPASS or QUEUE_APPEND with a targetCmdId
    return action + " takes no targetCmdId (got '" + target + "')"


def target_needed(action: str) -> str:
    # BAD_SYNTAX: QUEUE_INSERT, QUEUE_REPLACE or QUEUE_DELETE without a targetCmdId
    return action + ' needs a targetCmdId'


def unknown_insert_target(target: str) -> str:
    # BAD_SYNTAX: QUEUE_INSERT after a command neither pending nor running (nor 'head')
    return "unknown targetCmdId '" + target + "' (pending ids, the running one or 'head')"


def unknown_target(target: str) -> str:
    # BAD_SYNTAX: QUEUE_REPLACE or QUEUE_DELETE of a command neither pending nor running
    return "unknown targetCmdId '" + target + "' (not pending or running)"


def queue_full(limit: int) -> str:
    # EXEC_FAILED: QUEUE_APPEND or QUEUE_INSERT with the queue at its limit
    return 'queue full (' + str(limit) + ' pending); retry later'


def bypass_full(limit: int) -> str:
    # EXEC_FAILED: QUEUE_BYPASS with the bypass limit's commands running
    return str(limit) + ' commands already running beside the queue; retry later'


def target_not_abortable(target: str) -> str:
    # EXEC_FAILED: QUEUE_REPLACE or QUEUE_DELETE of a running command that is not abortable
    return "target '" + target + "' is running and not abortable"


# EXEC_FAILED: a command arriving while the bridge stops; CANCELED: each pending command at shutdown
ASSET_SHUTTING_DOWN: Final = 'asset shutting down'


def unknown_subsystem(subsystem: str) -> str:
    # BAD_SYNTAX: a subsystem the asset does not have
    return "unknown subsystem '" + subsystem + "'"


def unknown_command(command: str, subsystem: str) -> str:
    # BAD_SYNTAX: a command the subsystem's type does not have
    return "unknown command '" + command + "' for subsystem '" + subsystem + "'"


def argument_count_one(command: str, got: int) -> str:
    # BAD_SYNTAX: a command of one parameter sent with another number of arguments
    return command + ' takes 1 argument, got ' + str(got)


def argument_count(command: str, count: int, got: int) -> str:
    # BAD_SYNTAX: a command of 0 or several parameters sent with another number of arguments
    return command + ' takes ' + str(count) + ' arguments, got ' + str(got)


def argument_type(index: int, name: str, expected: str, got: str) -> str:
    # BAD_SYNTAX: an argument whose DataType is not its parameter's (index from 1, DataType names)
    return 'argument ' + str(index) + ' (' + name + ') must be ' + expected + ', got ' + got


def argument_invalid(index: int, name: str, why: str) -> str:
    # BAD_SYNTAX: an argument outside its parameter's shape, range or allowed values (why: one of the three below)
    return 'argument ' + str(index) + ' (' + name + '): ' + why


def string_too_long(size: int, limit: int) -> str:
    # argument_invalid's why: a RAPID_STRING longer than its String128 carries
    return str(size) + ' bytes (max ' + str(limit) + ')'


def not_one_of(value: str, allowed: str) -> str:
    # argument_invalid's why: a value outside the allowed values (value as Python's repr, allowed '|'-separated)
    return value + ' not one of ' + allowed


def out_of_range(value: str, low: str, high: str) -> str:
    # argument_invalid's why: a number (or a vector's element) outside min..max (Python's {:g}; -inf/inf for an open end)
    return value + ' not in [' + low + ', ' + high + ']'


def access_not_allowed(source: str, subsystem: str, command: str) -> str:
    # BAD_SYNTAX: the descriptor's allow-list does not let this cmdSrc send this command
    return 'RAPID access violation: ' + source + ' may not send ' + subsystem + '/' + command


def access_no_control(source: str) -> str:
    # BAD_SYNTAX: a command from a source that does not hold control (assets with AccessControl)
    return 'RAPID access violation: ' + source + ' does not have control (send requestControl)'


def control_granted(source: str) -> str:
    # OK: requestControl with no controller (or from the controller)
    return 'control granted to ' + source


def request_already_queued(controller: str) -> str:
    # OK: requestControl from a source already waiting
    return 'request already queued; ' + controller + ' has control'


def requests_full(limit: int) -> str:
    # EXEC_FAILED: requestControl with AccessControlState.requestors full
    return str(limit) + ' requests already queued'


def request_queued(controller: str) -> str:
    # OK: requestControl while another source has control
    return 'request queued; ' + controller + ' has control'


def control_taken_from(before: str) -> str:
    # OK: grabControl from another source than the controller
    return 'control taken from ' + before


# OK: grabControl with no controller (or from the controller)
CONTROL_TAKEN: Final = 'control taken'


def no_control(source: str) -> str:
    # EXEC_FAILED: releaseControl or transferControl from a source that does not hold control
    return source + ' does not have control'


def control_released_to(controller: str) -> str:
    # OK: releaseControl, control passing to the first requestor
    return 'control released to ' + controller


# OK: releaseControl with no requestor waiting
CONTROL_RELEASED: Final = 'control released'

# EXEC_FAILED: transferControl to an empty (or blank) name
NEW_CONTROLLER_EMPTY: Final = 'newController is empty'

# EXEC_FAILED: transferControl to a name AccessControlState's String32 cannot hold
NEW_CONTROLLER_TOO_LONG: Final = 'newController longer than 31 bytes'


def control_transferred(controller: str) -> str:
    # OK: transferControl
    return 'control transferred to ' + controller


def replaced_by(cmd_id: str) -> str:
    # CANCELED: a pending command a QUEUE_REPLACE took the place of (the replacing cmdId)
    return 'replaced by ' + cmd_id


def deleted_by(cmd_id: str) -> str:
    # CANCELED: a pending command a QUEUE_DELETE removed (the deleting cmdId)
    return 'deleted by ' + cmd_id


def target_canceled(target: str) -> str:
    # OK: the QUEUE_DELETE of a pending command
    return target + ' canceled'


def cancel_requested(target: str) -> str:
    # OK: the QUEUE_DELETE of a running abortable command (its own final ack follows)
    return target + ' cancel requested; handler has not stopped yet'


# REQUEUED: a suspendable queued command a QUEUE_BYPASS command on its subsystem stopped
PREEMPTED: Final = 'preempted; back in the queue'

# CANCELED: each pending command Queue/cancelAll removed
CANCELED_BY_CANCEL_ALL: Final = 'cancelAll'

# CANCELED: each pending Mobility command Mobility/stopAllMotion removed
CANCELED_BY_STOP_ALL_MOTION: Final = 'stopAllMotion'


def handlers_asked_to_stop(count: int) -> str:
    # OK: Queue/cancelAll with abortable commands running (joined to the next by '; ')
    return str(count) + ' handler(s) asked to stop, not stopped yet'


def non_abortable_running(count: int) -> str:
    # OK: Queue/cancelAll with commands running that are not abortable
    return str(count) + ' non-abortable command(s) still running'


def motion_not_stopped(count: int) -> str:
    # OK (or the handler's completion): Mobility/stopAllMotion completing while canceled motion handlers still run, after the message and '; '
    return str(count) + ' motion handler(s) not stopped yet'


# OK: Mobility/stopAllMotion whose handler is the generated stub (or missing)
NO_HARDWARE_STOP: Final = 'motion commands canceled; no hardware stop handler'

# OK: Admin/shutdown
SHUTTING_DOWN: Final = 'shutting down'

# CANCELED: a handler that returned after being told to stop, or raised Cancelled
CANCELED: Final = 'canceled'

# EXEC_FAILED: a handler that failed without saying why
FAILED: Final = 'failed'

# EXEC_FAILED: a command whose handler is the generated stub, or missing
NOT_IMPLEMENTED: Final = 'not implemented'


def handler_error(error_type: str, message: str) -> str:
    # EXEC_FAILED: a handler that raised an unexpected exception (its type's name and text)
    return 'handler error: ' + error_type + ': ' + message


# EXEC_FAILED: a C++ handler that threw something not a std::exception (a Python exception always has a type) (only the cpp runtime)
HANDLER_ERROR_UNKNOWN: Final = 'handler error: unknown exception'

# EXEC_FAILED: a C++ handler whose Result says ACK_COMPLETED_NOT (a Python handler cannot return one) (only the cpp runtime)
NO_COMPLETION: Final = 'handler gave no completion'

# EXEC_FAILED: a handler still running at its stop bound, or at the shutdown bound
DID_NOT_STOP: Final = 'handler did not stop'

# CANCELED: a command the journal shows accepted and not started when the asset went down
RESTARTED_QUEUED: Final = 'asset restarted before it ran'

# EXEC_FAILED: a command the journal shows running when the asset went down
RESTARTED_RUNNING: Final = 'asset restarted while it ran; outcome unknown'


def bridge_busy(count: int) -> str:
    # EXEC_FAILED: a command shed at the door, its writer's queue full (not run, its cmdId not remembered)
    return 'bridge busy: ' + str(count) + ' commands from this writer already waiting; retry later'


def source_silent(entry: str, age: float) -> str:
    # TextMessage MSG_WARN: a watched telemetry entry's source silent past its bound
    return entry + ' source silent for ' + format(age, '.1f') + ' s: samples stopped'


def source_back(entry: str) -> str:
    # TextMessage MSG_INFO: a silent entry's first current sample
    return entry + ' source back'
