"""Ack and queue-status vocabulary (enumerator names, as in the RAPID IDL) and Ack text."""
from __future__ import annotations

import re

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


# What no IDL string may carry: a lone surrogate (UTF-8 cannot encode it: Python's str of bytes
# decoded with surrogateescape, or half a pair) and NUL (it ends a C string: the C++ side of
# the wire and cyclonedds would cut or refuse it). Each becomes U+FFFD.
_INVALID = re.compile("[\x00\ud800-\udfff]")
REPLACEMENT = "\ufffd"


def valid(text: object) -> str:
    """text made valid for an IDL string: each lone surrogate and each NUL becomes U+FFFD;
    anything but a string is str() of it (one that cannot print says so)."""
    if not isinstance(text, str):
        try:
            text = str(text)
        except Exception as exc:
            text = f"<unprintable {type(text).__name__}: {type(exc).__name__}>"
    return _INVALID.sub(REPLACEMENT, text)


def clip(text: object, limit: int | None = MESSAGE_BYTES) -> str:
    """text as an Ack.message (or any bounded IDL string, `limit` its bound in bytes less the
    terminator; None: unbounded): made valid (valid()), then its first `limit` UTF-8 bytes,
    never cut inside a character."""
    text = valid(text)
    if limit is None:
        return text
    data = text.encode("utf-8")
    return text if len(data) <= limit else data[:limit].decode("utf-8", "ignore")


# Ack -> QueueState record status (rapid-protocol.md 5b), and the record's result.
STATUS_OF_ACK = {QUEUED: "Q_STATUS_INLINE", EXECUTING: "Q_STATUS_INPROCESS", REQUEUED: "Q_STATUS_PAUSED"}
STATUS_OF_COMPLETION = {OK: "Q_STATUS_SUCCEEDED", BAD_SYNTAX: "Q_STATUS_FAILED", EXEC_FAILED: "Q_STATUS_FAILED",
                        CANCELED: "Q_STATUS_CANCELED"}
RESULT_OF_COMPLETION = {OK: "Q_RESULT_SUCCEEDED", BAD_SYNTAX: "Q_RESULT_FAILED", EXEC_FAILED: "Q_RESULT_FAILED",
                        CANCELED: "Q_RESULT_FAILED"}
