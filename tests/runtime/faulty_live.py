"""Both sides of the live handler-fault tests (issue 42), each its own process on loopback:

    python -m tests.runtime.faulty_live bridge PYDIR PACKAGE [BRIDGE ARGS...]
        K10's bridge (rapid_runtime.bridge.main) with handlers that misbehave: pointCamera
        ignores cancel and never returns; takePicture writes a lone surrogate and a NUL into
        its progress and its result; stopAllMotion has no method (the generated stub's case).
    python -m tests.runtime.faulty_live ground CHECK PYDIR PACKAGE DOMAIN
        stuck     DELETE of the stuck pointCamera, then an APPEND behind it, a bad-text
                  picture, stopAllMotion, then Admin/shutdown while a second pointCamera is stuck
        sigterm   a stuck pointCamera and a pending picture; prints "armed" and waits for both
                  final acks (the test sends SIGTERM to the bridge meanwhile)
        Prints one JSON document (the acks of each command) as its last line.
"""
from __future__ import annotations

import importlib
import json
import sys
import threading

from tests.runtime.ground import load

F, S = "RAPID_FLOAT", "RAPID_STRING"
POINT = [(F, 0.1), (F, 0.0)]
PICTURE = [(S, "left"), (F, 0.0)]
WAIT = 30.0  # s: how long the ground waits for an ack it needs (a loaded machine)


def bridge(pydir: str, package: str, argv: list[str]) -> int:
    sys.path.insert(0, pydir)
    from rapid_runtime.bridge import main
    from rapid_runtime.handlers import Handlers
    tables = importlib.import_module(f"{package}.asset_tables")
    rapid = importlib.import_module(f"{package}.rapid")

    class Faulty(Handlers):
        def pan_tilt_camera_point_camera(self, ctx, pan, tilt):
            threading.Event().wait()  # ignores ctx.cancelled; never returns

        def pan_tilt_camera_take_picture(self, ctx, mode, exposure):
            ctx.progress("half \udcff done\x00")
            return f"{mode} \udcff picture\x00"

    return main(tables, rapid, Faulty, package, argv)


def _final(c, cid: str) -> list:
    return [list(a) for a in c.wait_final(cid, WAIT)]


def stuck(rapid, tables, qos, domain: int) -> dict:
    from rapid_runtime.commander import Commander
    c = Commander(rapid, qos, tables.name, "RapidWorkbench", domain)
    assert c.wait_for_asset(10)
    out: dict = {}
    _final(c, c.send("AccessControl", "requestControl"))
    a = c.send("PanCam", "pointCamera", POINT, action="QUEUE_APPEND")  # runs at once: the queue is empty
    d = c.send("Admin", "noOp", [], action="QUEUE_DELETE", target=a)
    out["delete"] = _final(c, d)
    b = c.send("PanCam", "takePicture", PICTURE, action="QUEUE_APPEND")  # behind the stuck one
    out["target"] = _final(c, a)
    out["later append"] = _final(c, b)
    out["stopAllMotion"] = _final(c, c.send("Mobility", "stopAllMotion", [], source="Intruder"))
    again = c.send("PanCam", "pointCamera", POINT, action="QUEUE_APPEND")  # stuck at shutdown
    out["shutdown"] = _final(c, c.send("Admin", "shutdown"))
    out["stuck at shutdown"] = _final(c, again)
    c.close()
    return out


def sigterm(rapid, tables, qos, domain: int) -> dict:
    from rapid_runtime.commander import Commander
    c = Commander(rapid, qos, tables.name, "RapidWorkbench", domain)
    assert c.wait_for_asset(10)
    _final(c, c.send("AccessControl", "requestControl"))
    a = c.send("PanCam", "pointCamera", POINT, action="QUEUE_APPEND")
    b = c.send("PanCam", "takePicture", PICTURE, action="QUEUE_APPEND")
    end = WAIT
    while end > 0 and not any(x[0] == "ACK_EXECUTING" for x in c.wait_acks(a, 0.05)):
        end -= 0.05
    print("armed", flush=True)
    out = {"running": _final(c, a), "pending": _final(c, b)}
    c.close()
    return out


def main() -> int:
    if sys.argv[1] == "bridge":
        return bridge(sys.argv[2], sys.argv[3], sys.argv[4:])
    check, python_dir, package, domain = sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5])
    _pkg, rapid, tables, qos = load(python_dir, package)
    result = {"stuck": stuck, "sigterm": sigterm}[check](rapid, tables, qos, domain)
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
