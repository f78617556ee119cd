"""Config serials: `serial` is the start time in seconds, and a config whose content
changes gets a new one (receivers ignore a config whose serial did not change), always
larger than the last. Samples copy their config's serial."""
from __future__ import annotations

import time
from typing import Callable


class Serials:
    def __init__(self, start: int | None = None, issued: Callable[[int], None] | None = None) -> None:
        """issued(serial): told of every serial given out (the journal records the highest,
        so a restarted bridge's serials are larger than any it used before)."""
        self.start = int(time.time()) if start is None else int(start)
        self._content: dict[str, object] = {}
        self._serial: dict[str, int] = {}
        self._last = self.start
        self._issued = issued
        if issued is not None:
            issued(self.start)

    def of(self, topic: str) -> int:
        """The serial of the topic's config (the start serial before it was set)."""
        return self._serial.get(topic, self.start)

    def update(self, topic: str, content: object) -> tuple[int, bool]:
        """(serial, changed): a new serial only when content differs from the last one."""
        if topic in self._content and self._content[topic] == content:
            return self._serial[topic], False
        if topic in self._content:
            self._last = max(self._last + 1, int(time.time()))
        self._content[topic] = content
        self._serial[topic] = self._last
        if self._issued is not None:
            self._issued(self._last)
        return self._serial[topic], True
