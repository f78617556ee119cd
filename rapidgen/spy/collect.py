"""From a Watcher's state (and the descriptors given with --asset) to a Snapshot: per
partition, its topics with endpoints, role, profile, rate and latest config; the
participants; the findings."""
from __future__ import annotations

import time

from rapidgen.spy.diagnose import diagnose
from rapidgen.spy.model import AssetView, EndpointView, Snapshot, TopicView, plain, profile_of, rate, role_of

MAX_SHOWN_OTHERS = 64  # partitions with readers only (nothing of ours reads there) shown
CONFIG_LINES = 200  # lines of one config in the text view (--json has it whole)


class Declared:
    """What the descriptors (--asset) say, by partition: roles, rates, config pairs."""

    def __init__(self, tables_list: list[dict]) -> None:
        self.roles: dict[tuple[str, str], str] = {}
        self.rates: dict[tuple[str, str], float] = {}
        self.pairs: dict[str, dict[str, str]] = {}
        self.names: dict[str, str] = {}
        self.profiles: dict[tuple[str, str], str] = {}
        for t in tables_list:
            part = t["ASSET"].get("partition", t["ASSET"]["name"])
            self.names[part] = t["ASSET"]["name"]
            for p in t["PUBLICATIONS"]:
                self.roles[(part, p["topic"])] = p["role"]
                self.profiles[(part, p["topic"])] = p["qos"]
                if p.get("rate"):
                    self.rates[(part, p["topic"])] = float(p["rate"])
            for e in t["TELEMETRY"]:
                cfg = e["topics"].get("config")
                for role, topic in e["topics"].items():
                    if cfg and role != "config":
                        self.pairs.setdefault(part, {})[topic] = cfg


def snapshot(w, declared: Declared) -> Snapshot:
    eps = [e for e in w.discovery.endpoints.values() if w.wanted(e.partitions)]
    by_part: dict[str, list] = {}
    for e in eps:
        for p in e.partitions:
            if p not in w.unread_partitions and (not w.partitions or p in w.partitions or p == "*"):
                by_part.setdefault(p, []).append(e)
    read = sorted(p for p in by_part if w.read(p))
    others = sorted(p for p in by_part if not w.read(p))  # readers only, wildcards: nothing of ours reads there
    parts = sorted(read + others[:MAX_SHOWN_OTHERS])
    shown = set(parts)
    roles = {}
    for part in parts:
        for e in by_part[part]:
            roles[(part, e.topic)] = role_of(e.type_name, declared.roles.get((part, e.topic)))
    snap = Snapshot(w.domain, time.monotonic() - w.started)
    mine: dict[str, set[str]] = {}
    left_out: dict[str, int] = {}  # partitions discovery did not keep (at least this many)
    for e in eps:
        mine.setdefault(e.participant, set()).update(e.partitions)
        left_out[e.participant] = max(left_out.get(e.participant, 0), e.qos.partitions_left_out)
    for key, p in sorted(w.discovery.participants.items()):
        props = p.properties
        theirs = mine.get(key, set())
        snap.participants.append({"key": key, "process": props.get("__ProcessName"), "pid": props.get("__Pid"),
                                  "host": props.get("__Hostname"), "partitions": sorted(theirs & shown),
                                  "other_partitions": len(theirs - shown) + left_out.get(key, 0)})
    for part in parts:
        here = by_part[part]
        asset = AssetView(part, declared.names.get(part, part), sorted({e.participant for e in here}))
        by_topic: dict[str, list] = {}
        for e in here:
            by_topic.setdefault(e.topic, []).append(e)
        for topic in sorted(by_topic):
            ends = by_topic[topic]
            type_name = next((e.type_name for e in ends if e.kind == "writer"), ends[0].type_name)
            tv = TopicView(part, topic, type_name, roles[(part, topic)],
                           declared_rate=declared.rates.get((part, topic)))
            for e in ends:
                prof, expected = profile_of(e.qos, e.type_name, e.kind == "writer",
                                            declared=declared.profiles.get((part, topic)))
                tv.expected_profile = expected
                view = EndpointView(e.kind, e.key, e.participant, e.type_name, e.qos.text(), prof)
                (tv.writers if e.kind == "writer" else tv.readers).append(view)
            streams = [st for st in w.streams.values() if st.topic == topic and st.partition == part]
            tv.samples = sum(st.count for st in streams)
            tv.decodable = (topic, type_name) not in w.undecodable
            for view in tv.writers:
                mine_seen = [s for st in streams for s in st.of_writer(view.key)]
                stamps = sorted(s.stamp for s in mine_seen if s.stamp is not None)
                view.rate = rate(stamps) if len(stamps) == len(mine_seen) else rate(sorted(s.at for s in mine_seen))
            rates = sorted(v.rate for v in tv.writers if v.rate is not None)
            tv.rate = rates[len(rates) // 2] if rates else None
            latest = w.latest(topic, part) if tv.role in ("config", "state") else None
            if latest is not None:
                tv.latest = plain(latest.sample)
                if tv.role == "config" and latest.asset and part not in declared.names:
                    asset.name = latest.asset
            asset.topics.append(tv)
        snap.assets.append(asset)
    snap.findings = diagnose(w, roles, declared.pairs)
    snap.dropped = w.dropped()
    snap.limits = w.limits()
    if len(others) > MAX_SHOWN_OTHERS:
        snap.limits.append(f"{len(others) - MAX_SHOWN_OTHERS} partition(s) with readers only not shown "
                           f"(cap {MAX_SHOWN_OTHERS})")
    return snap


def config_lines(cfg: dict) -> list[str]:
    """A decoded config as the operator reads it: CommandConfig as describe prints the
    command dictionary; joint definitions; value keys; other configs' scalar fields."""
    out = []
    if "availableSubsystemTypes" in cfg:
        users: dict[str, list[str]] = {}
        for s in cfg.get("availableSubsystems", []):
            users.setdefault(s["subsystemTypeName"], []).append(s["name"])
        for t in cfg["availableSubsystemTypes"]:
            out.append(f"{t['name']}: {', '.join(users.get(t['name'], [])) or '(no subsystem)'}")
            for c in t["commands"]:
                flags = [f for f in ("abortable", "suspendable") if c.get(f)]
                params = ", ".join(f"{p['key']}: {p['type']}" for p in c["parameters"])
                out.append(f"  {c['name']}({params})" + (f"  [{', '.join(flags)}]" if flags else ""))
    if "jointDefinitions" in cfg:
        out.append(f"joint group {cfg.get('jointGroupName', '')!r}: "
                   + ", ".join(f"{j['frameName']}/{j['dof']}" for j in cfg["jointDefinitions"]))
    if "valueKeys" in cfg:
        out.append("value keys: " + ", ".join(f"{v['key']}:{_union_type(v)}" for v in cfg["valueKeys"]))
    if not out:
        out.append(", ".join(f"{k}={v!r}" for k, v in cfg.items() if k != "hdr" and not isinstance(v, (dict, list))))
    if len(out) > CONFIG_LINES:
        out[CONFIG_LINES:] = [f"... {len(out) - CONFIG_LINES} more line(s) (--json has the whole config)"]
    return out


def _union_type(v: dict) -> str:
    """KeyTypePair has its type; KeyTypeValueTriple's is its value's discriminator."""
    if isinstance(v.get("type"), str):
        return v["type"].removeprefix("RAPID_")
    value = v.get("value")  # a union in plain form: {discriminator, value}
    d = value.get("discriminator") if isinstance(value, dict) else None
    return d.removeprefix("RAPID_") if isinstance(d, str) else "?"
