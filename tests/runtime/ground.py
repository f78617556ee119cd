"""The ground side of the live runtime tests, run as its own process against a running
bridge: `python -m tests.runtime.ground CHECK GENERATED_PYTHON_DIR PACKAGE DOMAIN`.
Prints one JSON document; the test asserts on it. CHECK:
  configs     join late, read every config the tables list (transient-local)
  commands    every command of the dictionary, valid arguments, BYPASS; acks of each
  malformed   (K10Red) the malformed/unauthorized kinds of docs/runtime.md; acks of each
"""
from __future__ import annotations

import importlib
import json
import math
import sys
import time


def load(python_dir: str, package: str):
    sys.path.insert(0, python_dir)
    pkg = importlib.import_module(package)
    rapid = importlib.import_module(f"{package}.rapid")
    tables_mod = importlib.import_module(f"{package}.asset_tables")
    qos = importlib.import_module(f"{package}.qos").RapidQos()
    from rapid_runtime.tables import Tables
    return pkg, rapid, Tables(tables_mod), qos


def source_for(tables) -> str:
    """A source the allow-list lets send everything (or any, without an allow-list)."""
    if tables.access is None:
        return "RapidGround"
    return next(r.source for r in tables.access.rules if "*" in r.allow)


def valid_value(p):
    if p.has_default:
        return p.default
    if p.allowed:
        return p.allowed[0]
    lo, hi = p.min, p.max
    if p.type == "RAPID_BOOL":
        return True
    if p.type == "RAPID_STRING":
        return "test"
    mid = 0.1 if (lo is None or lo <= 0.1) and (hi is None or hi >= 0.1) else (lo if lo is not None else hi)
    if p.type in ("RAPID_INT", "RAPID_LONGLONG"):
        return int(math.ceil(mid)) if lo is None or math.ceil(mid) >= lo else int(lo)
    if p.type == "RAPID_VEC3d":
        return [mid, 0.0 if lo is None or lo <= 0 else lo, 0.0 if lo is None or lo <= 0 else lo]
    if p.type == "RAPID_MAT33f":
        return [1.0, 0, 0, 0, 1.0, 0, 0, 0, 1.0] if (lo is None or lo <= 0) and (hi is None or hi >= 1) else [mid] * 9
    return float(mid)


def configs(rapid, tables, qos, domain: int) -> dict:
    from rapid_runtime import messages as M
    from rapid_runtime.dds import Node, type_class
    node = Node(rapid, qos, domain)
    readers = {t: (ty, node.reader(t, type_class(rapid, ty))) for t, (ty, _v) in tables.configs.items()}
    got, end = {}, time.monotonic() + 15
    while len(got) < len(readers) and time.monotonic() < end:
        for topic, (ty, r) in readers.items():
            if topic in got:
                continue
            for s in r.take(N=4):
                if type(s).__name__ == ty.split("::")[-1]:
                    want = M.config(rapid, ty, tables.configs[topic][1], s.hdr)
                    want = type(want).deserialize(want.serialize())  # float32 members rounded as on the wire
                    got[topic] = {"type": ty, "same": s == want, "serial": s.hdr.serial,
                                  "src": s.hdr.srcName, "asset": s.hdr.assetName}
        time.sleep(0.02)
    return {"expected": sorted(readers), "got": got}


def commands(rapid, tables, qos, domain: int) -> dict:
    from rapid_runtime.commander import Commander
    src = source_for(tables)
    c = Commander(rapid, qos, tables.name, src, domain)
    assert c.wait_for_asset(10), "no bridge matched"
    results = []

    def run(sub, entry, args=None):
        args = args if args is not None else [(p.type, valid_value(p)) for p in entry.params]
        cid = c.send(sub, entry.name, args)
        results.append({"command": f"{sub}/{entry.name}", "acks": c.wait_final(cid, 20)})

    control = tables.has_type("AccessControl")
    entries = list(tables.entries())
    by = {(e.subsystem_type, e.name): (s, e) for s, e in entries}
    if control:
        run(*by[("AccessControl", "requestControl")])
    last = [("AccessControl", "grabControl"), ("AccessControl", "transferControl"), ("AccessControl", "releaseControl"),
            ("AccessControl", "requestControl"), ("Admin", "shutdown")]
    for sub, e in entries:
        if (e.subsystem_type, e.name) not in last:
            run(sub, e)
    for key in last:
        if key in by:
            sub, e = by[key]
            run(sub, e, [("RAPID_STRING", src)] if key[1] == "transferControl" else None)
    c.close()
    return {"source": src, "results": results}


def malformed(rapid, tables, qos, domain: int) -> dict:
    from rapid_runtime.commander import Commander
    c = Commander(rapid, qos, tables.name, "RapidWorkbench", domain)
    assert c.wait_for_asset(10)
    F = "RAPID_FLOAT"
    out = {}

    def ask(kind, *a, expect_none=False, **kw):
        cid = c.send(*a, **kw)
        out[kind] = c.wait_acks(cid, 0.5) if expect_none else c.wait_final(cid, 10)
        return cid

    ask("control", "AccessControl", "requestControl")
    ask("wrong asset", "Admin", "echo", [("RAPID_STRING", "x")], asset="SomeOtherRover", expect_none=True)
    first = ask("first of a repeated id", "Admin", "echo", [("RAPID_STRING", "x")])
    ask("repeated cmdId", "Admin", "echo", [("RAPID_STRING", "y")], cmd_id=first, expect_none=True)  # its acks in 0.5 s
    ask("unknown subsystem", "Arm9", "echo", [])
    ask("unknown command", "Admin", "selfDestruct", [])
    ask("too few arguments", "PanCam", "pointCamera", [(F, 0.1)])
    ask("too many arguments", "PanCam", "pointCamera", [(F, 0.1), (F, 0.1), (F, 0.1)])
    ask("wrong type", "PanCam", "pointCamera", [("RAPID_DOUBLE", 0.1), (F, 0.1)])
    ask("out of range", "PanCam", "pointCamera", [(F, 9.0), (F, 0.1)])
    ask("not a number", "PanCam", "pointCamera", [(F, float("nan")), (F, 0.1)])
    ask("not allowed", "PanCam", "takePicture", [("RAPID_STRING", "infrared"), (F, 0.0)])
    ask("source not allowed this command", "Mobility", "simpleMove",
        [("RAPID_STRING", "site"), ("RAPID_VEC3d", [0.1, 0, 0])], source="ScienceBackroom")
    ask("unknown source", "Admin", "echo", [("RAPID_STRING", "x")], source="Intruder")
    ask("source without control", "PanCam", "pointCamera", [(F, 0.1), (F, 0.1)], source="MultiCenterCockpit")
    ask("bypass with target", "Admin", "noOp", [], target="abc")
    ask("append with target", "Admin", "noOp", [], action="QUEUE_APPEND", target="abc")
    ask("insert without target", "Admin", "noOp", [], action="QUEUE_INSERT")
    ask("replace unknown target", "Admin", "noOp", [], action="QUEUE_REPLACE", target="no-such-id")
    ask("delete unknown target", "Admin", "noOp", [], action="QUEUE_DELETE", target="no-such-id")
    ask("empty cmdId", "Admin", "noOp", [], cmd_id="")
    ask("release by non-controller", "AccessControl", "releaseControl", [], source="MultiCenterCockpit")
    ask("stopAllMotion from anyone", "Mobility", "stopAllMotion", [], source="Intruder")
    ask("still running", "Admin", "echo", [("RAPID_STRING", "alive")])
    c.close()
    return out


def main() -> int:
    check, python_dir, package, domain = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    _pkg, rapid, tables, qos = load(python_dir, package)
    result = {"configs": configs, "commands": commands, "malformed": malformed}[check](rapid, tables, qos, domain)
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
