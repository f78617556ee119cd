"""The asset's live CommandConfig and the tables it gives, merged with the descriptor's."""
from __future__ import annotations

import sys
import time


def live_config(commander, rapid, asset: str, seconds: float) -> dict | None:
    """The asset's CommandConfig (transient-local: a late reader still gets it), or None."""
    from rapid_runtime import messages as M
    from rapid_runtime.commander import COMMAND_CONFIG_TOPIC

    from rapid_runtime.untrusted import GuardedReader

    guard = GuardedReader(commander.node.reader(COMMAND_CONFIG_TOPIC, rapid.CommandConfig), dedupe=True, batch=4)
    end = time.monotonic() + seconds
    try:
        while time.monotonic() < end:
            for s in guard.take():  # a config that does not decode is someone else's: dropped, said below
                if s.hdr.assetName == asset:
                    return M.config_plain(s)
            time.sleep(0.02)
        return None
    finally:
        for note in guard.summary():
            print(f"cmd: {note}", file=sys.stderr)


def merged_tables(data: dict, config: dict) -> dict:
    """The tables with the live config's subsystems and commands; a parameter keeps the
    descriptor's unit, range, allowed values and default when its name and type agree."""
    known = data["COMMANDS"]
    commands: dict[str, dict] = {}
    for t in config["availableSubsystemTypes"]:
        out = commands[t["name"]] = {}
        for c in t["commands"]:
            mine = known.get(t["name"], {}).get(c["name"], {})
            by_name = {p["name"]: p for p in mine.get("parameters", ())}
            params = []
            for p in c["parameters"]:
                d = by_name.get(p["key"])
                params.append(dict(d) if d and d["type"] == p["type"] else
                               {"name": p["key"], "arg": p["key"], "type": p["type"]})
            out[c["name"]] = {"method": mine.get("method", c["name"]), "abortable": c["abortable"],
                              "suspendable": c["suspendable"], "parameters": params}
    subsystems = {s["name"]: s["subsystemTypeName"] for s in config["availableSubsystems"]}
    return dict(data, SUBSYSTEMS=subsystems, COMMANDS=commands)
