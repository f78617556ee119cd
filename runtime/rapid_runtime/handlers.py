"""What an asset's handlers see: the base class, the command's context, the failure.

A handler method takes (ctx, **named arguments) and
- returns normally: COMPLETED/OK (a returned string becomes Ack.message);
- raises CommandFailed(reason): COMPLETED/EXEC_FAILED with the reason;
- notices ctx.cancelled (abortable commands: DELETE, cancelAll, stopAllMotion, or a
  preempting command) and returns or raises Cancelled: COMPLETED/CANCELED (or REQUEUED
  when it was preempted and will run again).
It runs in its own thread, may run long and report progress (EXECUTING acks).
"""
from __future__ import annotations

import threading


class CommandFailed(Exception):
    """Raised by a handler: the command failed (COMPLETED/EXEC_FAILED, str(exc) as the message)."""


class Cancelled(Exception):
    """Raised by a handler (or ctx.check()) when it stops because it was cancelled."""


class CommandContext:
    def __init__(self, cmd, entry, progress) -> None:
        self.cmd = cmd  # rapid_runtime.command.Cmd
        self.entry = entry  # rapid_runtime.tables.CommandEntry
        self.subsystem: str = cmd.subsystem  # the instance (LeftArm) of the type the method serves (Arm)
        self.source: str = cmd.cmd_src
        self.cancelled = threading.Event()
        self._progress = progress

    def progress(self, text: str) -> None:
        """Report progress: an EXECUTING ack carrying text (cut to 127 bytes)."""
        self._progress(text)

    def sleep(self, seconds: float) -> bool:
        """Wait, waking early on cancellation; True when not cancelled."""
        return not self.cancelled.wait(max(0.0, seconds))

    def check(self) -> None:
        """Raise Cancelled if the command was cancelled."""
        if self.cancelled.is_set():
            raise Cancelled()


class Handlers:
    """Base of the generated (user-owned) handlers class. A command whose method is
    missing answers EXEC_FAILED "not implemented"."""

    def on_start(self, bridge) -> None:
        """Called once the bridge is up (bridge.telemetry publishes samples)."""

    def on_stop(self) -> None:
        """Called when the bridge stops (Admin/shutdown, a signal)."""
