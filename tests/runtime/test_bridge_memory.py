"""The bridge's resident memory stays flat under a stream of commands (docs/runtime.md,
"Bounded memory"): K10's bridge with a window of 256 commands takes 4,500 Admin/noOp on
loopback from another process (tests/runtime/memory_load.py), its VmRSS and VmHWM read from
/proc while it runs. After ten windows (2,500 commands) the high-water mark may not climb by
more than GROWTH_KIB (1 MiB) over the next 2,000: at the ~1.2 KB a command the bridge used
to keep (a Cyclone writer's instance state), it climbed by about 2.4 MB; now it climbs by
some tens of KiB. Why not from the first full window: the heap settles over the first few
windows (about 700 KiB from 1,000 to 1,500 commands, 100-900 KiB more up to 2,500), journal
or not (the same with --no-journal), while the ack writers' generations (a new writer every
64 commands, retired a window later) and their matches in Cyclone turn over; measured from
1,000 it once grew 1212 KiB in CI.
bench/bridge_memory.py runs the same for 100,000 commands with the default window."""
from __future__ import annotations

import json
import subprocess
import sys

from tests.runtime.memory_load import ROOT

DOMAIN = 191
COMMANDS = 4500
SETTLED = 2500  # ten windows: the heap has settled (see above)
GROWTH_KIB = 1024


def test_resident_memory_stays_flat_under_thousands_of_commands():
    res = subprocess.run([sys.executable, "-m", "tests.runtime.memory_load", str(DOMAIN), str(COMMANDS), "500",
                          "--", "--command-window", "256"], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-4000:]
    got = json.loads(res.stdout.splitlines()[-1])
    assert got["answered"] == COMMANDS and got["alive"], got
    samples = got["samples"]
    full = next(s for s in samples if s[0] >= SETTLED)
    growth = samples[-1][2] - full[2]  # VmHWM: nothing higher in between, whenever it was reached
    assert growth < GROWTH_KIB, f"VmHWM grew {growth} KiB from {full[0]} to {COMMANDS} commands: {samples}"
