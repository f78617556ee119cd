"""Protocol rules: two asset descriptors compared (commands, telemetry, topics, QoS, DDS).

Commands are compared per subsystem through the effective command dictionary (after
`extends` and the standard RAPID types); telemetry entries are matched by kind and suffix;
topics by full name, with QoS judged by DDS request/offered rules on both crossings (an
OLD writer with a NEW reader, a NEW writer with an OLD reader).
"""
from __future__ import annotations

from rapidgen.asset.resolved import LoadedAsset
from rapidgen.asset.spec import JointTelemetry, Telemetry, TypedValue
from rapidgen.diff.rules import Finding, rule
from rapidgen.qos.spec import default_library

DURABILITY = ("volatile", "transient_local", "transient", "persistent")


class ProtocolDiff:
    def __init__(self, old: LoadedAsset, new: LoadedAsset) -> None:
        self.old, self.new = old, new
        self.o, self.n = old.spec, new.spec
        self.out: list[Finding] = []

    def add(self, rule_id: str, subject: str, message: str, old, new) -> None:
        self.out.append(Finding(rule(rule_id), subject, message, old, new))

    def run(self) -> list[Finding]:
        o, n = self.o, self.n
        if o.domain != n.domain:
            self.add("PROTO-DOMAIN-01", o.name, f"DDS domain was {o.domain}, is now {n.domain}",
                     o.at("dds", "domain"), n.at("dds", "domain"))
        if o.partition != n.partition:
            self.add("PROTO-PART-01", o.name, f"partition was '{o.partition}', is now '{n.partition}'",
                     o.at("dds", "partition"), n.at("dds", "partition"))
        self.subsystems()
        self.telemetry()
        self.topics()
        self.access()
        return self.out

    # -- who may command ----------------------------------------------------------------
    def access(self) -> None:
        """PROTO-ACCESS-01 per source that may now send a command (present on both sides)
        that OLD refused it; "any other source" stands for the sources no rule names."""
        oa, na = self.old.access, self.new.access
        if oa is None:  # OLD let every source send everything: nothing can widen
            return
        if na is None:
            self.add("PROTO-ACCESS-01", "*", "access_control removed: any source may now send every command",
                     oa.loc, self.n.loc)
            return
        commands = sorted(_commands(self.old) & _commands(self.new))
        sources = sorted({r.source for r in oa.rules} | {r.source for r in na.rules})
        for source in [*sources, None]:
            gained = [f"{sub}/{cmd}" for sub, typ, cmd in commands
                      if _allowed(na, source, sub, cmd) and not _allowed(oa, source, sub, cmd)]
            if not gained:
                continue
            who = f"source '{source}'" if source is not None else "any source no rule names"
            shown = ", ".join(gained[:6]) + (f" and {len(gained) - 6} more" if len(gained) > 6 else "")
            rules = [r for r in na.rules if r.source == source]
            where = rules[0].at("allow") if rules else na.at("default")
            old_rules = [r for r in oa.rules if r.source == source]
            self.add("PROTO-ACCESS-01", source or "*", f"{who} may now send {shown}",
                     old_rules[0].at("allow") if old_rules else oa.loc, where)

    # -- commands -----------------------------------------------------------------------
    def subsystems(self) -> None:
        new_subs = {s.name: s for s in self.new.subsystems}
        otypes, ntypes = self.old.types, self.new.types
        seen: set[tuple[str, str]] = set()
        for s in self.old.subsystems:
            ns = new_subs.get(s.name)
            if ns is None:
                self.add("PROTO-SUBSYS-01", s.name, f"subsystem '{s.name}' removed", s.loc, self.n.loc)
                continue
            if s.type != ns.type:
                self.add("PROTO-SUBSYS-02", s.name, f"subsystem '{s.name}' was a {s.type}, is now a {ns.type}",
                         s.at("type"), ns.at("type"))
            ot, nt = otypes.get(s.type), ntypes.get(ns.type)
            if ot is None or nt is None or (s.type, ns.type) in seen:
                continue
            seen.add((s.type, ns.type))
            new_cmds = {c.name: c for c in nt.commands}
            for c in ot.commands:
                nc = new_cmds.get(c.name)
                sub = f"{ns.type}.{c.name}"
                if nc is None:
                    self.add("PROTO-CMD-01", sub, f"command '{c.name}' removed from {ns.type} (subsystem "
                             f"'{s.name}')", c.loc, nt.loc)
                    continue
                lost = [w for w in ("abortable", "suspendable") if getattr(c, w) and not getattr(nc, w)]
                if lost:
                    self.add("PROTO-CMD-02", sub, f"command '{sub}' is no longer {' or '.join(lost)}",
                             c.at(lost[0]), nc.at(lost[0]) if nc.has(lost[0]) else nc.loc)
                self.values(sub, c.parameters, nc.parameters, nc.loc, "PARAM")

    def values(self, owner: str, old: tuple, new: tuple, new_owner_loc, family: str) -> None:
        """Parameters (family PARAM) or telemetry value keys (family VALUE): positional lists."""
        new_by = {v.name: v for v in new}
        old_names = [v.name for v in old]
        common_old = [v.name for v in old if v.name in new_by]
        common_new = [v.name for v in new if v.name in old_names]
        what = "parameter" if family == "PARAM" else "value key"
        for v in old:
            if v.name not in new_by:
                self.add(f"PROTO-{family}-01", f"{owner}.{v.name}", f"{what} '{owner}.{v.name}' removed",
                         v.loc, new_owner_loc)
        if family == "PARAM":
            for v in new:
                if v.name not in old_names:
                    self.add("PROTO-PARAM-02", f"{owner}.{v.name}", f"parameter '{owner}.{v.name}' added",
                             None, v.loc)
        if common_old != common_new:
            k = next(i for i in range(len(common_new)) if common_old[i] != common_new[i])
            name = common_new[k]
            rid = "PROTO-PARAM-04" if family == "PARAM" else "PROTO-VALUE-02"
            self.add(rid, f"{owner}.{name}", f"{what} '{owner}.{name}' moved from position "
                     f"{old_names.index(name) + 1} to {[v.name for v in new].index(name) + 1}",
                     old[old_names.index(name)].loc, new_by[name].loc)
        for v in old:
            nv = new_by.get(v.name)
            if nv is not None:
                self.value(f"{owner}.{v.name}", v, nv, family)

    def value(self, sub: str, o: TypedValue, n: TypedValue, family: str) -> None:
        if o.type != n.type:
            rid = "PROTO-PARAM-03" if family == "PARAM" else "PROTO-VALUE-03"
            self.add(rid, sub, f"type of '{sub}' was {o.type}, is now {n.type}", o.at("type"), n.at("type"))
        if (o.unit or "") != (n.unit or ""):
            rid = "PROTO-PARAM-07" if family == "PARAM" else "PROTO-VALUE-04"
            self.add(rid, sub, f"unit of '{sub}' was {o.unit or 'none'}, is now {n.unit or 'none'}",
                     o.at("unit"), n.at("unit"))
        if family != "PARAM":
            return
        if _narrower(o.min, n.min, lambda a, b: b > a) or _narrower(o.max, n.max, lambda a, b: b < a):
            self.add("PROTO-PARAM-05", sub, f"range of '{sub}' was [{_num(o.min)}, {_num(o.max)}], is now "
                     f"[{_num(n.min)}, {_num(n.max)}]", o.at("range") if o.range_given else o.loc,
                     n.at("range") if n.range_given else n.loc)
        if n.allowed and (not o.allowed or set(o.allowed) - set(n.allowed)):
            gone = sorted(set(o.allowed) - set(n.allowed)) if o.allowed else ["any value"]
            self.add("PROTO-PARAM-06", sub, f"'{sub}' no longer allows {', '.join(map(str, gone))}",
                     o.at("allowed") if o.allowed else o.loc, n.at("allowed"))

    # -- telemetry ----------------------------------------------------------------------
    def telemetry(self) -> None:
        new_entries = {_entry_key(t): t for t in self.n.telemetry}
        for t in self.o.telemetry:
            nt = new_entries.get(_entry_key(t))
            if nt is None:
                continue  # its topics are gone: PROTO-TOPIC-01
            owner = t.suffix or t.kind
            if hasattr(t, "values") and hasattr(nt, "values"):
                self.values(owner, t.values, nt.values, nt.loc, "VALUE")
            if isinstance(t, JointTelemetry) and isinstance(nt, JointTelemetry):
                new_frames = [j.frame for j in nt.joints]
                for i, j in enumerate(t.joints):
                    if j.frame not in new_frames:
                        self.add("PROTO-JOINT-01", f"{owner}.{j.frame}", f"joint '{j.frame}' removed from "
                                 f"'{t.group}'", j.loc, nt.loc)
                    elif new_frames.index(j.frame) != i:
                        self.add("PROTO-JOINT-01", f"{owner}.{j.frame}", f"joint '{j.frame}' of '{t.group}' moved "
                                 f"from position {i + 1} to {new_frames.index(j.frame) + 1}", j.loc,
                                 nt.joints[new_frames.index(j.frame)].loc)

    def topics(self) -> None:
        old = {p.topic: p for p in self.old.publications}
        new = {p.topic: p for p in self.new.publications}
        lib = default_library()
        for topic, p in old.items():
            q = new.get(topic)
            if q is None:
                self.add("PROTO-TOPIC-01", topic, f"topic '{topic}' ({p.type}) is no longer published", p.loc,
                         self.n.loc)
                continue
            if p.type != q.type:
                self.add("PROTO-TOPIC-02", topic, f"topic '{topic}' carried {p.type}, now {q.type}", p.loc, q.loc)
            if p.qos == q.qos or not (lib.has_profile(p.qos) and lib.has_profile(q.qos)):
                continue
            (ow, orr), (nw, nr) = lib.effective(p.qos), lib.effective(q.qos)
            where_o, where_n = _qos_loc(p.source, p.role, p.loc), _qos_loc(q.source, q.role, q.loc)
            if not (_reliable_ok(nw, orr) and _reliable_ok(ow, nr)):
                self.add("PROTO-QOS-01", topic, f"'{topic}': {p.qos} ({ow.reliability} writer, {orr.reliability} "
                         f"reader) became {q.qos} ({nw.reliability} writer, {nr.reliability} reader)",
                         where_o, where_n)
            if not (_durable_ok(nw, orr) and _durable_ok(ow, nr)):
                self.add("PROTO-QOS-02", topic, f"'{topic}': {p.qos} ({ow.durability} writer, {orr.durability} "
                         f"reader) became {q.qos} ({nw.durability} writer, {nr.durability} reader)",
                         where_o, where_n)


def _entry_key(t: Telemetry) -> tuple:
    return (t.kind, t.suffix or "", getattr(t, "group", ""), getattr(t, "sensor", ""))


def _qos_loc(t: Telemetry | None, role: str, fallback):
    return t.at("qos", role) if t is not None and t.has("qos", role) else fallback


def _reliable_ok(writer, reader) -> bool:
    return reader.reliability != "reliable" or writer.reliability == "reliable"


def _durable_ok(writer, reader) -> bool:
    rank = {d: i for i, d in enumerate(DURABILITY)}
    return rank.get(writer.durability or "volatile", 0) >= rank.get(reader.durability or "volatile", 0)


def _narrower(old, new, tighter) -> bool:
    """A limit added, or moved inward."""
    return new is not None and (old is None or tighter(old, new))


def _commands(asset: LoadedAsset) -> set[tuple[str, str, str]]:
    """(subsystem, type, command) of every command the asset takes."""
    return {(s.name, s.type, c.name) for s in asset.subsystems for c in asset.types[s.type].commands}


def _matches(pattern: str, subsystem: str, command: str) -> bool:
    if pattern == "*":
        return True
    sub, _, cmd = pattern.partition("/")
    return sub in ("*", subsystem) and cmd in ("*", command)


def _allowed(spec, source: str | None, subsystem: str, command: str) -> bool:
    """The access list's answer (docs/asset-descriptor.md; the runtimes' rule); source None:
    a source no rule names. No section: every source may send everything."""
    if spec is None:
        return True
    rules = [r for r in spec.rules if r.source == source]
    if not rules:
        return spec.default == "allow"
    return any(_matches(p, subsystem, command) for r in rules for p in r.allow)


def _num(x) -> str:
    return "-" if x is None else f"{x:g}"


def protocol_diff(old: LoadedAsset, new: LoadedAsset) -> list[Finding]:
    return ProtocolDiff(old, new).run()
