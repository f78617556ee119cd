"""The ack writers: one DataWriter per generation of commands, so the bridge's memory stays flat.

Every Ack instance (key: the command's hdr.srcName, hdr.assetName and cmdId) is new, and a
Cyclone DDS 11 writer keeps about 1.2 KB for each instance it ever wrote while a reader is
matched, even after the instance is unregistered (measured: a writer that unregisters each
instance grows as fast as one that does not; deleting the writer gives it all back). So
commands are dealt to writer generations of `size` commands each: all the acks of one
command go through the writer of the generation that took it (a commander never sees
two writers answer one command), and a generation that is no longer current is deleted
once every command it took has been retired (manager.py: more than `window` commands
completed since). At most about window/size + 2 writers live, whatever the uptime.

Nothing here decides what is acked or retired: the manager does.
"""
from __future__ import annotations

import threading
from typing import Callable


class _Generation:
    __slots__ = ("writer", "taken", "live")

    def __init__(self, writer) -> None:
        self.writer = writer
        self.taken = 0  # commands dealt to it
        self.live = 0  # of those, not retired yet


class AckWriters:
    def __init__(self, make: Callable[[], object], size: int, delete: Callable[[object], None]) -> None:
        if size < 1:
            raise ValueError(f"generation size {size}: at least 1")
        self.make, self.size, self.delete = make, size, delete
        self.lock = threading.Lock()
        self.current = _Generation(make())
        # The next generation's writer is made half a generation early: ack readers have
        # discovered and matched it by the time it writes (a writer met late stalls them).
        self.next: object | None = None
        self.of: dict[tuple, _Generation] = {}  # command key -> its generation, until retired
        self.created = 1  # writers made so far (bench and tests read it)

    def writer_for(self, key: tuple):
        """The writer of the command's generation (the current one for a new command)."""
        with self.lock:
            gen = self.of.get(key)
            if gen is None:
                if self.current.taken >= self.size:
                    writer, self.next = self.next if self.next is not None else self._make(), None
                    old, self.current = self.current, _Generation(writer)
                    self._drop_if_done(old)
                elif self.next is None and self.current.taken >= self.size // 2:
                    self.next = self._make()
                gen = self.of[key] = self.current
                gen.taken += 1
                gen.live += 1
            return gen.writer

    def _make(self):
        self.created += 1
        return self.make()

    def retire(self, key: tuple):
        """The command's acks need not be kept: its writer (to unregister the instance), or
        None when it was never written. A finished generation is deleted afterwards (drop())."""
        with self.lock:
            gen = self.of.get(key)
            return None if gen is None else gen.writer

    def drop(self, key: tuple) -> None:
        """After retire(): forget the command; delete its generation's writer if it was the
        last live command of a generation no longer current."""
        with self.lock:
            gen = self.of.pop(key, None)
            if gen is None:
                return
            gen.live -= 1
            self._drop_if_done(gen)

    def _drop_if_done(self, gen: _Generation) -> None:
        if gen is not self.current and gen.live == 0:
            self.delete(gen.writer)

    def writers(self) -> list:
        """Every writer still alive (stop() waits for their acks to be delivered)."""
        with self.lock:
            return list({id(g): g.writer for g in [*self.of.values(), self.current]}.values())

    def close(self) -> None:
        """Delete the writer made early (stop())."""
        with self.lock:
            spare, self.next = self.next, None
        if spare is not None:
            self.delete(spare)
