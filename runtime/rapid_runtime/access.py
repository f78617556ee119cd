"""Who may command the asset.

Two independent gates (docs/runtime.md):
- the descriptor's allow-list (`access_control`): which cmdSrc may send which
  `Subsystem/command`; static privileges, checked on every command;
- the controller (assets with an AccessControl subsystem): only the source holding
  control may command, except AccessControl's own commands and the asset itself.
Mobility/stopAllMotion passes both: stopping is always allowed.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from rapid_runtime import texts
from rapid_runtime.tables import AccessSpec

MAX_REQUESTORS = 16  # AccessControlState.requestors is a String32Sequence16
NO_CONTROLLER = ""


def always_allowed(subsystem_type: str, command: str) -> bool:
    return subsystem_type == "Mobility" and command == "stopAllMotion"


def _matches(pattern: str, subsystem: str, command: str) -> bool:
    if pattern == "*":
        return True
    sub, _, cmd = pattern.partition("/")
    return sub in ("*", subsystem) and cmd in ("*", command)


def allowed(spec: AccessSpec | None, source: str, subsystem: str, command: str) -> bool:
    """The allow-list's answer; no access_control section allows every source."""
    if spec is None:
        return True
    rules = [r for r in spec.rules if r.source == source]
    if not rules:
        return spec.default == "allow"
    return any(_matches(p, subsystem, command) for r in rules for p in r.allow)


@dataclass
class Control:
    """The controller and the queue of requestors; each method returns None on success or
    the reason it failed (EXEC_FAILED), and says in `note` what happened."""

    controller: str = NO_CONTROLLER
    requestors: list[str] = field(default_factory=list)

    def holds(self, source: str) -> bool:
        return self.controller != NO_CONTROLLER and source == self.controller

    def request(self, source: str) -> tuple[str | None, str]:
        if self.controller in (NO_CONTROLLER, source):
            self._give(source)
            return None, texts.control_granted(source)
        if source in self.requestors:
            return None, texts.request_already_queued(self.controller)
        if len(self.requestors) >= MAX_REQUESTORS:
            return texts.requests_full(MAX_REQUESTORS), ""
        self.requestors.append(source)
        return None, texts.request_queued(self.controller)

    def grab(self, source: str) -> tuple[str | None, str]:
        before = self.controller
        self._give(source)
        return None, texts.control_taken_from(before) if before not in (NO_CONTROLLER, source) else texts.CONTROL_TAKEN

    def release(self, source: str) -> tuple[str | None, str]:
        if not self.holds(source):
            return texts.no_control(source), ""
        nxt = self.requestors.pop(0) if self.requestors else NO_CONTROLLER
        self.controller = nxt
        return None, texts.control_released_to(nxt) if nxt else texts.CONTROL_RELEASED

    def transfer(self, source: str, new: str) -> tuple[str | None, str]:
        if not self.holds(source):
            return texts.no_control(source), ""
        if not new.strip():
            return texts.NEW_CONTROLLER_EMPTY, ""
        if len(new.encode("utf-8")) > 31:
            return texts.NEW_CONTROLLER_TOO_LONG, ""
        self._give(new)
        return None, texts.control_transferred(new)

    def _give(self, source: str) -> None:
        self.controller = source
        if source in self.requestors:
            self.requestors.remove(source)
