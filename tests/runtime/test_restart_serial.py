"""The configs' serial after a restart (rapid_runtime.journal.restart_serial, what the bridge
starts its Serials with): the one asked for; else past the last one the journal knows and no
smaller than the time; else the bridge's default. The C++ and Rust runtimes' restart_serial
are tested alike (tests/cpp_runtime, rapid_runtime's cargo tests)."""
from __future__ import annotations

import os

from rapid_runtime.journal import Journal, Recovered, restart_serial


def test_a_restart_serial_is_past_the_journal_s_last_one_and_no_older_than_the_time(tmp_path):
    lines: list[str] = []
    journal, _ = Journal.open(tmp_path, "K10Red", 0, 16, lines.append)
    assert journal is not None, lines
    journal.start(1001)
    journal.serial(1002)  # a config changed while it ran
    journal.sync()
    os.close(journal.fd)  # a crash: no stop record
    _, recovered = Journal.open(tmp_path, "K10Red", 0, 16, lines.append)
    assert recovered.last_serial == 1002
    assert restart_serial(None, recovered, now=1000) == 1003
    assert restart_serial(None, recovered, now=5000.7) == 5000
    assert restart_serial(7, recovered, now=5000) == 7  # --serial given: as it is
    assert restart_serial(None, Recovered(), now=5000) is None  # no journal: the bridge's default
