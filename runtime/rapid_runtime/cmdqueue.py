"""The pending queue: ordered runs, with the positions INSERT, REPLACE and DELETE name."""
from __future__ import annotations

from typing import TYPE_CHECKING, Callable

from rapid_runtime.acks import HEAD

if TYPE_CHECKING:  # (the manager imports this queue)
    from rapid_runtime.manager import Run


class Pending:
    def __init__(self) -> None:
        self.items: list[Run] = []  # front first

    def __len__(self) -> int:
        return len(self.items)

    def __iter__(self):
        return iter(list(self.items))

    def find(self, cmd_id: str) -> Run | None:
        return next((r for r in self.items if r.cmd.cmd_id == cmd_id), None)

    def append(self, run: Run) -> None:
        self.items.append(run)

    def push_front(self, run: Run) -> None:
        self.items.insert(0, run)

    def insert_after(self, target: str, run: Run) -> bool:
        """After the pending command `target`; at the front for "head" (or for the command
        now running, which is ahead of every pending one). False: target not pending."""
        if target == HEAD:
            self.items.insert(0, run)
            return True
        for i, r in enumerate(self.items):
            if r.cmd.cmd_id == target:
                self.items.insert(i + 1, run)
                return True
        return False

    def replace(self, target: str, run: Run) -> Run | None:
        """Put run where target is; returns the removed target, or None."""
        for i, r in enumerate(self.items):
            if r.cmd.cmd_id == target:
                self.items[i] = run
                return r
        return None

    def remove(self, run: Run) -> None:
        self.items.remove(run)

    def pop_ready(self, busy: Callable[[str], bool]) -> Run | None:
        """The front run, removed, unless its subsystem is busy(subsystem) (a bypass command
        preempted it): the queue runs in order, so nothing behind it starts either."""
        if self.items and not busy(self.items[0].cmd.subsystem):
            return self.items.pop(0)
        return None
