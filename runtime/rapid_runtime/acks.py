"""Ack and queue-status vocabulary (enumerator names, as in the RAPID IDL) and Ack text."""
from __future__ import annotations

QUEUED, EXECUTING, REQUEUED, COMPLETED = "ACK_QUEUED", "ACK_EXECUTING", "ACK_REQUEUED", "ACK_COMPLETED"
NOT, OK, BAD_SYNTAX, EXEC_FAILED, CANCELED = ("ACK_COMPLETED_NOT", "ACK_COMPLETED_OK", "ACK_COMPLETED_BAD_SYNTAX",
                                              "ACK_COMPLETED_EXEC_FAILED", "ACK_COMPLETED_CANCELED")

BYPASS, APPEND, DELETE, INSERT, REPLACE = ("QUEUE_BYPASS", "QUEUE_APPEND", "QUEUE_DELETE", "QUEUE_INSERT",
                                           "QUEUE_REPLACE")
ACTIONS = (BYPASS, APPEND, DELETE, INSERT, REPLACE)
HEAD = "head"  # INSERT's target naming the front of the queue (rapid-protocol.md section 4)

# Ack.message is a String128: at most 127 bytes on the wire (Astrobee copies 128 bytes
# unterminated, so a full 128 would lose its terminator there). Python's cyclonedds refuses
# to encode one over 128 characters, or one with a lone surrogate, and the ack is lost: every
# message goes through clip() before it is written (manager.py), handler results included.
MESSAGE_BYTES = 127


def clip(text: object, limit: int = MESSAGE_BYTES) -> str:
    """text as an Ack.message: its first `limit` UTF-8 bytes, never cut inside a character;
    what UTF-8 cannot encode (a lone surrogate, e.g. from bytes decoded with
    surrogateescape) becomes '?'; anything but a string is str() of it."""
    data = (text if isinstance(text, str) else str(text)).encode("utf-8", "replace")
    return data[:limit].decode("utf-8", "ignore")


# Ack -> QueueState record status (rapid-protocol.md 5b), and the record's result.
STATUS_OF_ACK = {QUEUED: "Q_STATUS_INLINE", EXECUTING: "Q_STATUS_INPROCESS", REQUEUED: "Q_STATUS_PAUSED"}
STATUS_OF_COMPLETION = {OK: "Q_STATUS_SUCCEEDED", BAD_SYNTAX: "Q_STATUS_FAILED", EXEC_FAILED: "Q_STATUS_FAILED",
                        CANCELED: "Q_STATUS_CANCELED"}
RESULT_OF_COMPLETION = {OK: "Q_RESULT_SUCCEEDED", BAD_SYNTAX: "Q_RESULT_FAILED", EXEC_FAILED: "Q_RESULT_FAILED",
                        CANCELED: "Q_RESULT_FAILED"}
