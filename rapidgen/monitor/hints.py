"""What the descriptors given with --asset add to the live data: the command dictionary's
units, ranges, allowed values, defaults and descriptions (the live CommandConfig carries
names and types only), the telemetry values' units and warning/critical thresholds, and the
access-control sources (offered as cmdSrc choices)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

from rapid_runtime.thresholds import threshold_level


def _threshold(t) -> dict | None:
    return None if t is None else {"below": t.below, "above": t.above}


def level_of(value: float | None, hint: dict | None) -> str:
    """ok | warning | critical of a value against its hint's thresholds: the runtime's rule
    (rapid_runtime.thresholds, the ROS 2 ground node's too; NaN is critical where a threshold is set)."""
    if value is None or not hint:
        return "ok"
    return threshold_level(value, _bounds(hint.get("warning")), _bounds(hint.get("critical")))[0]


def _bounds(t: dict | None) -> tuple[float | None, float | None] | None:
    return None if t is None else (t["below"], t["above"])


@dataclass
class AssetHints:
    name: str
    partition: str
    commands: dict  # the tables' COMMANDS: type -> command -> entry
    subsystems: dict  # subsystem -> type
    values: dict[str, dict] = field(default_factory=dict)  # value key -> unit, min, max, warning, critical
    sources: list[str] = field(default_factory=list)
    config: dict | None = None  # the CommandConfig the descriptor's bridge publishes (plain form)


class Hints:
    def __init__(self, assets: list[AssetHints] | None = None) -> None:
        self.by_partition = {a.partition: a for a in assets or ()}

    @classmethod
    def of(cls, tables_and_specs: Sequence[tuple[dict, object]]) -> "Hints":
        """From (generated tables, rapidgen.asset LoadedAsset.spec) pairs."""
        out = []
        for tables, spec in tables_and_specs:
            asset = tables["ASSET"]
            h = AssetHints(asset["name"], asset.get("partition") or asset["name"], tables["COMMANDS"],
                           tables["SUBSYSTEMS"],
                           sources=[r["source"] for r in (tables.get("ACCESS") or {}).get("rules", ())],
                           config=((tables.get("CONFIGS") or {}).get("rapid_command_config") or {}).get("value"))
            for entry in getattr(spec, "telemetry", ()):
                for v in getattr(entry, "values", ()):
                    h.values[v.name] = {"unit": v.unit, "min": v.min, "max": v.max, "description": v.description,
                                        "warning": _threshold(v.warning), "critical": _threshold(v.critical)}
            out.append(h)
        return cls(out)

    def declared(self, partition: str) -> bool:
        """The partition is an --asset's."""
        return partition in self.by_partition

    def config_differs(self, partition: str, config: dict) -> str | None:
        """How a live CommandConfig (plain form) differs from the --asset descriptor's (None:
        the same, or no descriptor). RAPID arguments are positional: a parameter list in
        another order sends each value into another parameter."""
        a = self.by_partition.get(partition)
        if a is None or a.config is None:
            return None
        return config_difference(a.config, config)

    def value(self, partition: str, key: str) -> dict | None:
        a = self.by_partition.get(partition)
        return a.values.get(key) if a else None

    def commands_for(self, partition: str, config: dict | None) -> dict:
        """The page's command dictionary: the live CommandConfig (plain form) with the
        descriptor's hints where name and type agree; the descriptor's alone until a live
        config arrives; nothing without either."""
        a = self.by_partition.get(partition)
        sources = a.sources if a else []
        if config is None:
            if a is None:
                return {"origin": None, "subsystems": [], "sources": sources}
            types = {t: [{"name": c, "abortable": e["abortable"], "suspendable": e["suspendable"],
                          "parameters": [{"key": p["name"], "type": p["type"]} for p in e["parameters"]]}
                         for c, e in cmds.items()] for t, cmds in a.commands.items()}
            subs = list(a.subsystems.items())
            origin = "descriptor"
        else:
            types = {t["name"]: t["commands"] for t in config["availableSubsystemTypes"]}
            subs = [(s["name"], s["subsystemTypeName"]) for s in config["availableSubsystems"]]
            origin = "live"
        out = []
        for sub, tname in subs:
            known = a.commands.get(tname, {}) if a else {}
            commands = []
            for c in types.get(tname, ()):
                mine = known.get(c["name"], {})
                by_name = {p["name"]: p for p in mine.get("parameters", ())}
                params = []
                for p in c["parameters"]:
                    d = by_name.get(p["key"])
                    hint = d if d and d["type"] == p["type"] else {}
                    params.append({"name": p["key"], "type": p["type"], "unit": hint.get("unit"),
                                   "min": hint.get("min"), "max": hint.get("max"),
                                   "allowed": list(hint.get("allowed") or ()), "default": hint.get("default"),
                                   "has_default": bool(hint.get("has_default")),
                                   "description": hint.get("description") or ""})
                commands.append({"name": c["name"], "abortable": c["abortable"], "suspendable": c["suspendable"],
                                 "description": mine.get("description", ""), "parameters": params})
            out.append({"subsystem": sub, "type": tname, "commands": commands})
        return {"origin": origin, "subsystems": out, "sources": sources}

    def param(self, commands: dict, subsystem: str, command: str) -> list[dict] | None:
        """A command's parameters from a dictionary commands_for() made (None: unknown)."""
        for s in commands.get("subsystems", ()):
            if s["subsystem"] == subsystem:
                for c in s["commands"]:
                    if c["name"] == command:
                        return c["parameters"]
        return None


def _config_shape(config: dict) -> tuple[dict, dict]:
    subs = {str(x.get("name")): str(x.get("subsystemTypeName")) for x in config.get("availableSubsystems", ())}
    types = {}
    for t in config.get("availableSubsystemTypes", ()):
        types[str(t.get("name"))] = {str(c.get("name")): (bool(c.get("abortable")), bool(c.get("suspendable")),
                                                         [(str(p.get("key")), str(p.get("type")))
                                                          for p in c.get("parameters", ())])
                                     for c in t.get("commands", ())}
    return subs, types


def _params(ps: list) -> str:
    return ", ".join(f"{k} ({t.removeprefix('RAPID_')})" for k, t in ps) or "none"


def config_difference(expected: dict, live: dict, most: int = 3) -> str | None:
    """The first differences (at most `most`) between two CommandConfigs in plain form, as
    text for the operator; None when they say the same (order of subsystems, types and
    commands aside; parameters in order)."""
    want_subs, want_types = _config_shape(expected)
    got_subs, got_types = _config_shape(live)
    out: list[str] = []
    for sub in sorted(set(want_subs) | set(got_subs)):
        if sub not in got_subs:
            out.append(f"subsystem {sub} missing")
        elif sub not in want_subs:
            out.append(f"subsystem {sub} not in the descriptor")
        elif want_subs[sub] != got_subs[sub]:
            out.append(f"subsystem {sub} has type {got_subs[sub]}, the descriptor says {want_subs[sub]}")
    for tname in sorted(set(want_types) | set(got_types)):
        want, got = want_types.get(tname), got_types.get(tname)
        if want is None or got is None:
            out.append(f"subsystem type {tname} {'missing' if got is None else 'not in the descriptor'}")
            continue
        for cmd in sorted(set(want) | set(got)):
            if cmd not in got:
                out.append(f"{tname}/{cmd} missing")
            elif cmd not in want:
                out.append(f"{tname}/{cmd} not in the descriptor")
            elif got[cmd][2] != want[cmd][2]:
                out.append(f"{tname}/{cmd} parameters are {_params(got[cmd][2])}; the descriptor says "
                           f"{_params(want[cmd][2])}")
            elif got[cmd][:2] != want[cmd][:2]:
                out.append(f"{tname}/{cmd} abortable/suspendable differ from the descriptor")
    if not out:
        return None
    return "; ".join(out[:most]) + (f" (and {len(out) - most} more)" if len(out) > most else "")
