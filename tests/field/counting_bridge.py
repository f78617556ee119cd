"""A seed's real bridge (rapid_runtime.bridge.main, the package's tables and QoS) with the
simulated robot behind it, which also writes a line per handler run to FIELD_EXEC_LOG:
`run CMDID MONOTONIC` as a command starts executing. The tests count those lines: each command must
run exactly once, whatever the link did to its packets.

    python -m tests.field.counting_bridge PACKAGE [bridge options]   (FIELD_SIM_SPEED: speed)"""
from __future__ import annotations

import importlib
import os
import sys
import threading
import time

from rapid_runtime.bridge import main
from rapid_runtime.simulate import Simulator
from rapid_runtime.tables import Tables


class CountingSimulator(Simulator):
    def __init__(self, tables: Tables, speed: float, log_path: str) -> None:
        super().__init__(tables, speed)
        self._log = open(log_path, "a", buffering=1, encoding="utf-8")  # a line each, written at once
        self._log_lock = threading.Lock()

    def run(self, ctx, entry, kw: dict):
        with self._log_lock:
            self._log.write(f"run {ctx.cmd.cmd_id} {time.monotonic():.3f}\n")  # one clock for every namespace
        return super().run(ctx, entry, kw)


if __name__ == "__main__":
    package = sys.argv[1]
    tables = importlib.import_module(f"{package}.asset_tables")
    rapid = importlib.import_module(f"{package}.rapid")
    speed = float(os.environ.get("FIELD_SIM_SPEED", "1"))
    sys.exit(main(tables, rapid, lambda: CountingSimulator(Tables(tables), speed, os.environ["FIELD_EXEC_LOG"]),
                  package=package, argv=sys.argv[2:]))
