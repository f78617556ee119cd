"""The restart tests' bridge: the generated Restarter package served by rapid_runtime, its
Worker/work handler appending the cmdId to EXECFILE as it starts (one O_APPEND write: a
kill -9 loses nothing written), so the test counts how often each command ran.
With RESTART_STALL=PREFIX a command whose cmdId starts with PREFIX is taken from the DDS
reader and never reaches the manager (nor the journal): `stalled CMDID` goes to EXECFILE
and the intake blocks, as a process being killed would leave it. RESTART_PACKAGE=PKG serves
another generated package instead (its handler stubs; the runtime answers Admin/noOp).

    python -m tests.field.restart_bridge PYDIR EXECFILE [BRIDGE ARGS...]
"""
from __future__ import annotations

import importlib
import os
import sys
import threading


def main(argv: list[str]) -> int:
    pydir, exec_file, rest = argv[0], argv[1], argv[2:]
    sys.path.insert(0, pydir)
    from rapid_runtime.bridge import main as bridge_main
    from rapid_runtime.handlers import Handlers
    package = os.environ.get("RESTART_PACKAGE", "rapid_restarter")
    tables = importlib.import_module(f"{package}.asset_tables")
    rapid = importlib.import_module(f"{package}.rapid")
    fd = os.open(exec_file, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o644)

    class Worker(Handlers):
        def worker_work(self, ctx, ms: int) -> str:
            os.write(fd, f"{ctx.cmd.cmd_id}\n".encode())
            if not ctx.sleep(ms / 1000):
                return "interrupted"
            return "worked"

    stall = os.environ.get("RESTART_STALL")
    if stall:
        from rapid_runtime.manager import CommandManager
        receive = CommandManager.receive

        def stalled(self, cmd) -> None:
            if cmd.cmd_id.startswith(stall):
                os.write(fd, f"stalled {cmd.cmd_id}\n".encode())
                threading.Event().wait()  # until the test kills the process
            receive(self, cmd)
        CommandManager.receive = stalled  # type: ignore[method-assign]

    handlers = Worker if package == "rapid_restarter" else Handlers
    return bridge_main(tables, rapid, handlers, package=package, argv=rest)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
