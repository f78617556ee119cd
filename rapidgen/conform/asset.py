"""What the descriptor (through the generated tables) says the asset does: its commands,
who may send them, its configs and telemetry. Plain dicts in, small helpers out."""
from __future__ import annotations

import math
from dataclasses import dataclass

RUNNER_SOURCE = "RapidConformance"
PAIRED_KINDS = ("agent", "position", "joint")  # telemetry with a config that describes it


@dataclass(frozen=True)
class Cmd:
    subsystem: str
    type: str
    name: str
    params: tuple[dict, ...]
    abortable: bool = False
    standard: bool = False


class AssetFacts:
    def __init__(self, tables: dict) -> None:
        self.t = tables
        self.name: str = tables["ASSET"]["name"]
        self.partition: str = tables["ASSET"].get("partition", self.name)
        self.subsystems: dict[str, str] = dict(tables["SUBSYSTEMS"])
        self.access = tables.get("ACCESS")
        self.configs: dict[str, tuple[str, dict]] = {t: (c["type"], c["value"]) for t, c in tables["CONFIGS"].items()}
        self.publications: list[dict] = list(tables["PUBLICATIONS"])
        self.telemetry: list[dict] = list(tables["TELEMETRY"])

    def commands(self) -> list[Cmd]:
        out = []
        for sub, typ in self.subsystems.items():
            for name, c in self.t["COMMANDS"].get(typ, {}).items():
                out.append(Cmd(sub, typ, name, tuple(c["parameters"]), c.get("abortable", False), c.get("standard", False)))
        return out

    def command(self, typ: str, name: str) -> Cmd | None:
        return next((c for c in self.commands() if c.type == typ and c.name == name), None)

    def has_type(self, typ: str) -> bool:
        return typ in self.subsystems.values()

    # ---- who may send what -------------------------------------------------------------
    def allowed(self, source: str, cmd: Cmd) -> bool:
        if self.access is None:
            return True
        rule = next((r for r in self.access["rules"] if r["source"] == source), None)
        if rule is None:
            return self.access.get("default", "deny") == "allow"
        return any(a in ("*", f"{cmd.subsystem}/*", f"{cmd.subsystem}/{cmd.name}") for a in rule["allow"])

    def runner_source(self) -> str:
        """A source the allow-list lets send everything (the one with the most rights)."""
        if self.access is None or self.access.get("default") == "allow":
            return RUNNER_SOURCE
        cmds = self.commands()
        rules = sorted(self.access["rules"], key=lambda r: -sum(self.allowed(r["source"], c) for c in cmds))
        return rules[0]["source"] if rules else RUNNER_SOURCE

    def other_source(self, cmd: Cmd, besides: str) -> str | None:
        """Another source allowed to send cmd (to be refused for lack of control only)."""
        if self.access is None or self.access.get("default") == "allow":
            return RUNNER_SOURCE + "B"
        return next((r["source"] for r in self.access["rules"]
                     if r["source"] != besides and self.allowed(r["source"], cmd)), None)

    # ---- commands a check can send -----------------------------------------------------
    def refusable(self, besides: str) -> tuple[Cmd, str] | None:
        """(a harmless command, another source the allow-list lets send it): that source can
        only be refused for lack of control."""
        cands = [self.command("Admin", "noOp"), self.command("Admin", "echo"), self.harmless()]
        for c in [c for c in cands if c is not None]:
            other = self.other_source(c, besides)
            if other is not None:
                return c, other
        return None

    def harmless(self) -> Cmd | None:
        """A command that completes OK quickly and moves nothing, else the simplest command
        (fewest parameters) that is not an administrative or control one."""
        for typ, name in (("Admin", "noOp"), ("Admin", "echo")):
            c = self.command(typ, name)
            if c is not None:
                return c
        skip = {"Admin", "AccessControl", "Queue", "Mobility"}
        cands = [c for c in self.commands() if c.type not in skip]
        return min(cands, key=lambda c: len(c.params)) if cands else None

    def with_params(self, motion: bool = True) -> Cmd | None:
        """A harmless command that takes arguments (for count/type checks); motion False: never
        a command that moves the asset (is_motion)."""
        echo = self.command("Admin", "echo")
        if echo is not None and echo.params:
            return echo
        cands = [c for c in self.commands() if c.params and c.type not in ("AccessControl", "Queue")
                 and (motion or not is_motion(c))]
        return min(cands, key=lambda c: len(c.params)) if cands else None

    def long_running(self) -> list[tuple[Cmd, list]]:
        """The commands that run for a while (long drives), each with the arguments sent without
        a descriptor's conformance section (--allow-motion): 1000 m ahead (or the range's end)."""
        out = []
        for name in ("simpleMove", "move"):
            c = self.command("Mobility", name)
            if c is not None:
                args = []
                for p in c.params:
                    if p["type"] == "RAPID_VEC3d":
                        hi = p.get("max")
                        args.append((p["type"], [float(hi) if hi is not None else 1000.0, 0.0, 0.0]))
                    else:
                        args.append((p["type"], valid_value(p)))
                out.append((c, args))
        return out

    def sample_topics(self, paired: bool = True) -> list[dict]:
        """Publications that carry telemetry at a declared rate (role sample or state):
        paired, those of the kinds RAPID pairs with a config (agent, position, joint);
        else the others (images, text, extension types)."""
        out = []
        for p in self.publications:
            entry = self.entry_of(p["topic"])
            if p["role"] in ("sample", "state") and p.get("rate") and entry is not None:
                if (entry["kind"] in PAIRED_KINDS) == paired:
                    out.append(p)
        return out

    def config_of(self, topic: str) -> str | None:
        """The config topic a sample/state topic pairs with (same telemetry entry)."""
        for t in self.telemetry:
            if topic in t["topics"].values():
                return t["topics"].get("config")
        return None

    def entry_of(self, topic: str) -> dict | None:
        return next((t for t in self.telemetry if topic in t["topics"].values()), None)


def is_motion(cmd: Cmd) -> bool:
    """A command that moves the asset: sent only when allowed (the descriptor's conformance
    section or --allow-motion). rapidgen.asset.conformance.is_motion says which."""
    from rapidgen.asset.conformance import is_motion as moves
    return moves(cmd.type, cmd.name)


def _end(lo: float | None, hi: float | None) -> float:
    """The range's lower end, else its upper one (a range outside 0.1 has one)."""
    end = lo if lo is not None else hi
    if end is None:
        raise ValueError("a parameter range with neither end")
    return end


def valid_value(p: dict):
    """A value the parameter accepts: its default, its first allowed value, else one
    inside its range."""
    if p.get("has_default"):
        return p["default"]
    if p.get("allowed"):
        return p["allowed"][0]
    lo: float | None = p.get("min")
    hi: float | None = p.get("max")
    t = p["type"]
    if t == "RAPID_BOOL":
        return True
    if t == "RAPID_STRING":
        return "conformance"
    mid = 0.1 if (lo is None or lo <= 0.1) and (hi is None or hi >= 0.1) else _end(lo, hi)
    if t in ("RAPID_INT", "RAPID_LONGLONG"):
        v = int(math.ceil(mid))
        return v if (lo is None or v >= lo) and (hi is None or v <= hi) else int(_end(lo, hi))
    zero = 0.0 if lo is None or lo <= 0 else float(lo)
    if t == "RAPID_VEC3d":
        return [float(mid), zero, zero]
    if t == "RAPID_MAT33f":
        return [1.0, 0, 0, 0, 1.0, 0, 0, 0, 1.0] if (lo is None or lo <= 0) and (hi is None or hi >= 1) else [float(mid)] * 9
    return float(mid)


def valid_args(cmd: Cmd) -> list[tuple[str, object]]:
    return [(p["type"], valid_value(p)) for p in cmd.params]


def wrong_type(dtype: str) -> tuple[str, object]:
    """A value of another DataType than dtype."""
    return ("RAPID_INT", 1) if dtype != "RAPID_INT" else ("RAPID_STRING", "1")
