"""A private network namespace holding only `lo` (multicast routed to it), so ROS 2's Fast
DDS and the RAPID side's Cyclone DDS keep their default discovery and still never leave
this machine (../shared/dds-local). Named uniquely, removed on exit with what runs in it."""
from __future__ import annotations

import itertools
import os
import subprocess
from contextlib import contextmanager

_COUNT = itertools.count()


@contextmanager
def namespace():
    """Yields the command prefix that runs a program inside the namespace."""
    name = f"rgros2-{os.getpid()}-{next(_COUNT)}"
    subprocess.run(["ip", "netns", "add", name], check=True)
    try:
        for cmd in (["ip", "link", "set", "lo", "up"], ["ip", "link", "set", "lo", "multicast", "on"],
                    ["ip", "route", "add", "224.0.0.0/4", "dev", "lo"]):
            subprocess.run(["ip", "netns", "exec", name, *cmd], check=True)
        yield ["ip", "netns", "exec", name]
    finally:
        pids = subprocess.run(["ip", "netns", "pids", name], capture_output=True, text=True).stdout.split()
        for pid in pids:  # only what this namespace holds: what the test started in it
            try:
                os.kill(int(pid), 9)
            except (ProcessLookupError, ValueError):
                pass
        subprocess.run(["ip", "netns", "del", name], check=False)
