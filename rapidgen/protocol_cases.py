"""The protocol specification's cases (runtime/spec/cases/*.yaml) read, checked and
written out as the plain JSON every runtime's driver replays (runtime/spec/README.md).

    cases = load_cases()                       # every case, defaults filled in, args typed
    python -m rapidgen.protocol_cases json OUT.json

Arguments are typed here, from the seed's generated tables (the asset_tables module the
Python runtime reads), so a driver never guesses a RAPID type. Errors are located
(file:line:col) and end the load: a case that is not what it says must not be skipped.
"""
from __future__ import annotations

import functools
import importlib.util
import json
import os
import sys
import zlib
from pathlib import Path

import jsonschema

from rapidgen.yamlread import load_yaml
from rapidgen.diagnostics import DiagnosticSink, SourceLoc

ROOT = Path(__file__).resolve().parents[1]
SPEC = ROOT / "runtime" / "spec"
CASES = SPEC / "cases"
# seed -> (generated package folder, package): the tables each driver builds for that name
# (oddity: not a robot, runtime/spec/assets/oddity.yaml, the shapes no seed robot has)
SEEDS = {"k10": ("k10", "rapid_k10red"), "chariot": ("chariot", "rapid_chariot"),
         "robonaut2": ("robonaut2", "rapid_robonaut2"), "oddity": ("spec-oddity", "rapid_oddity")}
DEFAULT_SOURCE = "RapidWorkbench"
# steps only a driver can take (a live runner cannot make a handler return, restart the asset or
# fill its door); a case with expectations it cannot see (serial, files, journal_file, log_count) is offline only; others
# it cannot see (calls, retired, log, no_log, pending, order, stopped) it skips
OFFLINE_ONLY = {"release", "idle", "restart", "shutdown", "refuse", "offer", "open", "refused", "disk"}
# a journal record's keys in the order the runtimes write them (docs/runtime.md, "Restarts")
RECORD_KEYS = ("k", "id", "src", "asset", "serial", "c", "m")
# what names the journal's default folder, in the order the runtimes read them
STATE_VARS = ("RAPID_STATE_DIR", "XDG_STATE_HOME", "HOME")


class CaseError(Exception):
    """A case file that is not a valid case (the message is located)."""


@functools.lru_cache(maxsize=None)
def _schema_validator() -> jsonschema.Draft202012Validator:
    return jsonschema.Draft202012Validator(json.loads((SPEC / "case.schema.json").read_text()))


@functools.lru_cache(maxsize=None)
def seed_tables(seed: str):
    """The seed's generated tables as the Python runtime reads them (rapid_runtime.tables)."""
    from rapid_runtime.tables import Tables
    folder, package = SEEDS[seed]
    path = ROOT / "generated" / folder / "python" / package / "asset_tables.py"
    spec = importlib.util.spec_from_file_location(f"_spec_tables_{package}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return Tables(module)


def _params(seed: str, subsystem: str, name: str) -> list[str]:
    """The parameter types of subsystem/name on the seed; [] for a command it does not have
    (a case that sends an unknown command gives its arguments' types itself)."""
    entry = seed_tables(seed).command(subsystem, name)
    return [p.type for p in entry.params] if entry is not None else []


def _typed(args: list, types: list[str], where: SourceLoc) -> list[dict]:
    out = []
    for i, a in enumerate(args):
        if isinstance(a, dict) and "json" in a:  # (a value YAML text cannot hold: a control character)
            try:
                out.append({"type": a["type"], "value": json.loads(a["json"])})
            except json.JSONDecodeError as exc:
                raise CaseError(f"{where}: argument {i + 1}'s `json` is not JSON: {exc.msg}") from None
        elif isinstance(a, dict):
            out.append({"type": a["type"], "value": a["value"]})
        elif i < len(types):
            value = float(a) if types[i] in ("RAPID_FLOAT", "RAPID_DOUBLE") and isinstance(a, int) and \
                not isinstance(a, bool) else a
            out.append({"type": types[i], "value": value})
        else:
            raise CaseError(f"{where}: argument {i + 1} has no declared parameter to type it: "
                            f"write it as {{type: RAPID_..., value: ...}}")
    return out


def _text(value) -> str:
    """A text of a case: a string, or `{json: '"..."'}` for one YAML text cannot hold (the
    project's YAML reader refuses control characters): a JSON string literal, escapes and all."""
    if isinstance(value, dict):
        try:
            text = json.loads(value["json"])
        except json.JSONDecodeError as exc:
            raise CaseError(f"`json: {value['json']}` is not a JSON string: {exc.msg}") from None
        if not isinstance(text, str):
            raise CaseError(f"`json: {value['json']}` is not a JSON string")
        return text
    return value


def _ack(text) -> dict:
    text = _text(text)
    head, sep, message = text.partition(": ")
    status, _, completion = head.partition(" ")
    prefix = bool(sep) and message.endswith("*")
    return {"status": status, "completion": completion or None,
            "message": (message[:-1] if prefix else message) if sep else None, "prefix": prefix}


def _handler(h) -> dict:
    if isinstance(h, str):
        return {"kind": h, "text": "", "texts": []}
    (kind, value), = h.items()
    return {"kind": kind, "text": "" if isinstance(value, list) else _text(value),
            "texts": [_text(v) for v in value] if isinstance(value, list) else []}


def _steps(case: dict, seed: str, source: str, doc, path: tuple) -> list[dict]:
    name = case.get("asset_name", seed_tables(seed).name)
    out: list[dict] = []
    for i, step in enumerate(case["steps"]):
        (op, body), = step.items()
        where = doc.loc((*path, "steps", i))
        try:
            out.extend(_step(op, body, case, seed, source, name, where))
        except CaseError as exc:
            if str(exc).startswith("`json"):  # (a text's: located here)
                raise CaseError(f"{where}: {exc}") from None
            raise
    return out


def _step(op: str, body, case: dict, seed: str, source: str, name: str, where: SourceLoc) -> list[dict]:
    out: list[dict] = []
    if op == "restart" and "door" in case:  # (a door serves one manager: the drivers do not rebuild it)
        raise CaseError(f"{where}: a case with a `door:` cannot restart the asset")
    if op in ("offer", "open") and "door" not in case:
        raise CaseError(f"{where}: `{op}` needs the case's `door:` (the door the commands are offered at)")
    if op in ("send", "refuse", "offer"):
        sub, _, cname = body.get("cmd", "Admin/noOp").partition("/")
        src = body.get("src", source)
        s = {"op": op, "id": body["id"], "src": src, "src_name": body.get("src_name", src), "subsystem": sub,
             "name": cname, "asset": body.get("asset", name)}
        if op == "offer":
            s["writer"] = body["writer"]
        if op in ("send", "offer"):
            s.update(args=_typed(body.get("args", []), _params(seed, sub, cname), where),
                     action=body.get("action", "QUEUE_BYPASS"), target=body.get("target", ""),
                     handler=_handler(body.get("handler", "ok")))
        else:
            s.update(args=[], action="QUEUE_BYPASS", target="", why=body.get("why", "bridge busy"))
        if "times" in body:  # the same command n times, cmdIds <id>-1 ... <id>-n
            out.extend({**s, "id": f"{body['id']}-{k}"} for k in range(1, body["times"] + 1))
        else:
            out.append(s)
    elif op == "acks":
        for cid, acks in body.items():
            out.append({"op": "acks", "id": cid, "acks": [_ack(a) for a in acks]})
    elif op == "release":
        out.append({"op": op, "id": body})
    elif op == "shutdown":
        out.append({"op": op, "timeout_ms": body.get("timeout_ms", -1)})
    elif op == "restart":  # kill -9, or (`clean`) a clean stop, then a start on the journal
        out.append({"op": op, "clean": body == "clean"})
    elif op in ("idle", "open"):
        out.append({"op": op})
    elif op == "queue":
        out.append({"op": op, **{k: body[k] for k in ("code", "pending", "active", "completed", "statuses") if k in body}})
    elif op == "control":
        out.append({"op": op, **{k: body[k] for k in ("controller", "requestors") if k in body}})
    elif op == "calls":
        out.append({"op": op, "calls": [{"id": c[0], "values": c[1]} for c in body]})
    elif op in ("retired", "pending"):
        out.append({"op": op, "ids": body})
    elif op in ("log", "no_log"):
        out.append({"op": op, "text": body})
    elif op == "log_count":
        out.append({"op": op, "text": body["text"], "count": body["count"]})
    elif op == "disk":  # from here the journal's fdatasync fails (EIO), or its writes (ENOSPC), or neither
        if not any(k in case for k in ("journal", "state")) and not any("restart" in st for st in case["steps"]):
            raise CaseError(f"{where}: `disk` needs a journal (the case's `journal:`, `state:` or a restart)")
        out.append({"op": op, "failing": body == "failing", "full": body == "full"})
    elif op == "order":
        out.append({"op": op, "ids": body})
    elif op == "stopped":
        out.append({"op": op, "count": body})
    elif op == "serial":  # the configs' serial since the latest start: a number, or the clock's seconds then
        out.append({"op": op, "clock": body == "clock", "value": 0 if body == "clock" else body})
    elif op == "files":
        if not any(k in case for k in ("journal", "state")) and not any("restart" in st for st in case["steps"]):
            raise CaseError(f"{where}: `files` needs a journal folder (the case's `journal:`, `state:` or a restart)")
        out.append({"op": op, "names": body})
    elif op == "refused":  # the asset does not start: its manager refuses the case's options
        if len(case["steps"]) != 1:
            raise CaseError(f"{where}: `refused` is a case's only step (the asset never started)")
        out.append({"op": op, "text": body})
    elif op == "journal_file":
        if not any(k in case for k in ("journal", "state")) and not any("restart" in st for st in case["steps"]):
            raise CaseError(f"{where}: `journal_file` needs a journal (the case's `journal:`, `state:` or a restart)")
        out.append({"op": op, "file": journal_file_name(name), "mode": body.get("mode"), "tail": body.get("tail", False),
                    "lines": None if "lines" not in body else
                    [[journal_field(k, _text(v)) for k, v in line.items()] for line in body["lines"]]})
    return out


def journal_field(key: str, value) -> str:
    """A record's field as the runtimes write it in a journal line (`"m":"a\\u0001"`): what a
    `journal_file` expectation looks for in a line, between `{` or `,` and `,` or `}`."""
    return json.dumps({key: value}, separators=(",", ":"), ensure_ascii=True)[1:-1]


def journal_file_name(asset: str) -> str:
    """The journal's file name on domain 0 (docs/runtime.md, "Restarts"; each runtime's file_name)."""
    return "".join(c if c.isascii() and (c.isalnum() or c in "_.-") else "_" for c in asset)[:64] + "-domain0.journal"


def journal_line(record: dict) -> str:
    """A journal line as docs/runtime.md ("Restarts") defines it: the CRC-32 (zlib's) of the
    compact, ASCII-escaped JSON record in 8 lowercase hex digits, a space, the JSON, a newline."""
    text = json.dumps(record, separators=(",", ":"), ensure_ascii=True)
    return f"{zlib.crc32(text.encode()):08x} {text}\n"


def _journal(case: dict, seed: str, source: str) -> dict | None:
    """The journal the asset's first start finds (the case's `journal:`): its file name (one per
    asset and domain; the drivers start on domain 0), its text, and `new`: the text of the
    `<file>.new` a crash in the middle of a compaction left (`journal_new:`), or None."""
    if "journal" not in case and "journal_new" not in case:
        return None
    name = case.get("asset_name", seed_tables(seed).name)
    new = _journal_text(case["journal_new"], name, source) if "journal_new" in case else None
    return {"file": journal_file_name(name), "text": _journal_text(case.get("journal", []), name, source), "new": new}


def _journal_text(entries: list, name: str, source: str) -> str:
    """Journal lines: a record (`k`, fields left out filled in) as the runtimes write it, `json:`
    a record's JSON text with its CRC added (and `separator:` instead of the space after it, a
    damaged one), `raw:` a line written as it is, `torn:` bytes without a newline."""
    text = ""
    for entry in entries:
        if "raw" in entry:  # a line as it is (a damaged one)
            text += entry["raw"] + "\n"
            continue
        if "torn" in entry:  # a line's first bytes only, without its newline (a write cut short)
            text += entry["torn"]
            continue
        if "json" in entry:  # a record's JSON text as some writer spelled it, its CRC added
            text += f"{zlib.crc32(entry['json'].encode()):08x}{entry.get('separator', ' ')}{entry['json']}\n"
            continue
        rec = dict(entry)
        if rec["k"] in ("q", "x", "c"):
            rec.setdefault("src", source)
            rec.setdefault("asset", name)
            rec.setdefault("serial", 1)
            if rec["k"] == "c":
                rec.setdefault("c", "ACK_COMPLETED_OK")
                rec.setdefault("m", "")
        order = [k for k in RECORD_KEYS if k in rec] + [k for k in rec if k not in RECORD_KEYS]
        text += journal_line({k: rec[k] for k in order})
    return text


def _state(case: dict) -> dict | None:
    """Where the asset's journal is when it is started without a folder (the case's `state:`,
    the variables set besides HOME): docs/runtime.md ("Restarts", "Where"). The drivers set
    each of `set` to the folder of that name in the case's temporary folder, unset `unset`,
    and write the case's journal in `dir` (relative to it)."""
    if "state" not in case:
        return None
    given = [*case["state"], "HOME"]
    if "RAPID_STATE_DIR" in given:
        where = "RAPID_STATE_DIR"
    elif "XDG_STATE_HOME" in given:
        where = "XDG_STATE_HOME/rapid_runtime"
    else:
        where = "HOME/.local/state/rapid_runtime"
    return {"set": {v: v for v in given}, "unset": [v for v in STATE_VARS if v not in given], "dir": where}


def _live(case: dict, steps: list[dict]) -> bool:
    """Whether a live runner can replay the case against a running asset (README, "Live replay")."""
    # an asset started with options, under another name, on a journal or a state folder, with
    # a door or a given serial; a burst of `times` sends (a flood to a live asset: its conform run is kept short)
    if any(k in case for k in ("options", "asset_name", "journal", "journal_new", "state", "door", "serial")) or \
            any("times" in (step.get("send") or {}) for step in case["steps"]):
        return False
    for s in steps:
        # (records' statuses, completed records: the runner compares the pending and active cmdIds only)
        if s["op"] in OFFLINE_ONLY or s["op"] in ("serial", "files", "journal_file", "log_count") or "statuses" in s or "completed" in s:
            return False
        # a scripted handler, a QueueAction outside the enumeration (a typed DDS writer cannot send
        # it), another header srcName than cmdSrc: what a runner cannot make an asset do or send
        if s["op"] == "send" and (s["handler"]["kind"] != "ok" or s["action"] == "QUEUE_BOGUS" or s["src_name"] != s["src"]):
            return False
    return True


def load_file(path: Path) -> list[dict]:
    sink = DiagnosticSink()
    shown = os.path.relpath(path, ROOT) if path.is_relative_to(ROOT) else str(path)
    doc = load_yaml(str(path), shown, sink)
    if doc is None or sink.has_errors:
        raise CaseError("\n".join(str(d) for d in sink.errors) or f"{shown}: cannot be read")
    errors = sorted(_schema_validator().iter_errors(doc.data), key=lambda e: list(e.absolute_path))
    if errors:
        e = errors[0]
        raise CaseError(f"{doc.loc(tuple(e.absolute_path))}: {e.message[:300]}")
    data = doc.data
    assert isinstance(data, dict)  # (the schema says so)
    cases = []
    names: set[str] = set()
    for n, case in enumerate(data["cases"]):
        path_ = ("cases", n)
        if case["name"] in names:
            raise CaseError(f"{doc.loc((*path_, 'name'))}: a second case named {case['name']!r} in this file")
        names.add(case["name"])
        seed = case.get("asset", data.get("asset", "k10"))
        source = case.get("source", data.get("source", DEFAULT_SOURCE))
        steps = _steps(case, seed, source, doc, path_)
        low = [k for k, v in case.get("options", {}).items() if v < 1]
        if low and steps[0]["op"] != "refused":
            raise CaseError(f"{doc.loc((*path_, 'options', low[0]))}: {low[0]} {case['options'][low[0]]}: "
                            f"at least 1, or the case expects it `refused`")
        journal = _journal(case, seed, source)
        if journal is not None and "\r" in journal["text"] + (journal["new"] or ""):  # (the runtimes' line splitting differs there)
            raise CaseError(f"{doc.loc((*path_, 'journal'))}: a journal line holds a carriage return")
        door = case.get("door")  # (its limits left out: the runtime's own)
        live = _live(case, steps)
        cases.append({"file": path.name, "line": doc.loc(path_).line, "name": case["name"],
                      "rules": case.get("rules", []), "asset": seed,
                      "asset_name": case.get("asset_name"), "options": case.get("options", {}),
                      "serial": case.get("serial"),
                      "live": live, "journal": journal, "state": _state(case), "door": door, "steps": steps})
    return cases


def load_cases(folder: Path = CASES) -> list[dict]:
    return [c for f in sorted(folder.glob("*.yaml")) for c in load_file(f)]


def main(argv: list[str]) -> int:
    if len(argv) != 2 or argv[0] != "json":
        print("usage: python -m rapidgen.protocol_cases json OUT.json", file=sys.stderr)
        return 2
    try:
        cases = load_cases()
    except CaseError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    tmp = Path(argv[1] + ".tmp")
    tmp.write_text(json.dumps({"cases": cases}, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    tmp.replace(argv[1])
    print(f"{len(cases)} cases -> {argv[1]}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
