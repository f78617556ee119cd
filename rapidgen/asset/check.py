"""Checks of an AssetSpec against itself and the IDL model: names, commands, access control.

Telemetry checks live in check_telemetry.py, typed-value checks in check_values.py. Each
problem is one diagnostic at the YAML line and column of the offending value, with a hint
saying what to write instead.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from rapidgen.asset.check_streams import check_streams
from rapidgen.asset.check_telemetry import check_telemetry
from rapidgen.asset.check_values import ValueChecker
from rapidgen.asset.facts import fits, utf8_len
from rapidgen.asset.spec import CommandSpec, Located, SubsystemSpec, SubsystemTypeSpec
from rapidgen.asset.standard import STANDARD_TYPES
from rapidgen.diagnostics import DiagnosticSink, SourceLoc, did_you_mean

if TYPE_CHECKING:
    from rapidgen.asset.resolved import LoadedAsset

EPHEMERAL = (32768, 60999)  # Linux's default net.ipv4.ip_local_port_range


class Checker:
    def __init__(self, loaded: "LoadedAsset", sink: DiagnosticSink) -> None:
        self.loaded = loaded
        self.spec, self.facts, self.sink = loaded.spec, loaded.facts, sink
        self.values = ValueChecker(self.facts, sink)

    # -- shared helpers ---------------------------------------------------------------
    def bound(self, text: str, loc: SourceLoc, what: str, struct: str, member: str) -> None:
        """A name must fit the IDL string it is published in."""
        n = self.facts.str_bound(struct, member)
        if n is not None and not fits(text, n):
            self.sink.error("RG1106", f"{what} '{text}' is {utf8_len(text)} bytes; "
                            f"{struct.split('::')[-1]}.{member} holds at most {n - 1} (string<{n}>)",
                            loc, f"shorten it to {n - 1} bytes or fewer")

    def count(self, items: tuple, at, what: str, struct: str, member: str, hint: str = "drop some") -> bool:
        """Too many items for a bounded sequence: an error at the first one that does not fit."""
        n = self.facts.seq_bound(struct, member)
        if n is None or len(items) <= n:
            return True
        self.sink.error("RG1107", f"{len(items)} {what}; {struct.split('::')[-1]}.{member} holds at most {n}",
                        at(n), f"item {n + 1} is here; {hint}")
        return False

    def duplicates(self, items, key, what: str, field: str = "name", where: str = "") -> None:
        """One error per repeated name, at the repeat, naming the first line."""
        first: dict = {}
        for item in items:
            k = key(item)
            if k in first:
                shown = k if isinstance(k, str) else "/".join(k)
                self.sink.error("RG1101", f"duplicate {what} '{shown}'{where}",
                                item.at(field) if item.has(field) else item.loc,
                                f"first defined at line {first[k].loc.line}")
            else:
                first[k] = item

    # -- the asset ----------------------------------------------------------------------
    def run(self) -> None:
        spec = self.spec
        self.bound(spec.name, spec.at("asset", "name"), "asset name", "rapid::Header", "assetName")
        for i, tag in enumerate(spec.tags):
            self.bound(tag, spec.at("asset", "tags", i), "agent tag", "rapid::AgentConfig", "agentTags")
        self.count(spec.tags, lambda n: spec.at("asset", "tags", n), "agent tags", "rapid::AgentConfig", "agentTags")
        if spec.partition != spec.name:
            self.sink.warning("RG1401", f"DDS partition '{spec.partition}' differs from the asset name "
                              f"'{spec.name}'", spec.at("dds", "partition"),
                              "RAPID assets publish in a partition named after themselves; "
                              "ground tools subscribe by asset name")
        self.domain_ports()
        self.subsystem_types()
        self.subsystems()
        self.native()
        self.access_control()
        check_telemetry(self)
        check_streams(self)

    def domain_ports(self) -> None:
        """Fast DDS 2.9 announces no domain id and Cyclone DDS reads its ephemeral send
        socket: a domain whose well-known ports (RAPID's mapping, the first 20 participant
        indices) the kernel also hands out as ephemeral ones lets other domains in
        (docs/qos.md, "Domain ids on one host"; the C++ runtime warns too, ports.hpp)."""
        d = self.spec.domain
        first, last = 7400 + 250 * d, 7400 + 250 * d + 11 + 2 * 19
        if first <= EPHEMERAL[1] and last >= EPHEMERAL[0]:
            self.sink.warning("RG1403", f"DDS domain {d}'s RTPS ports ({first}-{last}) lie in Linux's default "
                              f"ephemeral port range ({EPHEMERAL[0]}-{EPHEMERAL[1]})", self.spec.at("dds", "domain"),
                              "a C++ (Fast DDS) participant on it can be discovered by a Cyclone DDS participant of "
                              "another domain on the same host; use 0-101 or 215-232")

    # -- subsystem types and commands -------------------------------------------------------
    def subsystem_types(self) -> None:
        spec = self.spec
        self.duplicates(spec.subsystem_types, lambda t: t.name, "subsystem type")
        local = {t.name for t in spec.subsystem_types}
        for t in spec.subsystem_types:
            self.bound(t.name, t.at("name"), "subsystem type name", "rapid::SubsystemType", "name")
            if t.name in STANDARD_TYPES:
                self.sink.error("RG1105", f"subsystem type '{t.name}' redefines the standard RAPID type",
                                t.at("name"), f"name it differently and write 'extends: {t.name}' "
                                "to add commands to the standard ones")
            if t.extends is not None and t.extends not in STANDARD_TYPES:
                what = "a type of this descriptor" if t.extends in local else "not a standard subsystem type"
                self.sink.error("RG1102", f"'extends: {t.extends}': {what}", t.at("extends"),
                                did_you_mean(t.extends, STANDARD_TYPES) or
                                f"only standard types can be extended: {', '.join(STANDARD_TYPES)}")
        for t in self.loaded.types.values():
            if not t.standard and t.loc.line > 0:
                self.commands(t)

    def commands(self, t: SubsystemTypeSpec) -> None:
        own = [c for c in t.commands if c.loc.line > 0]  # inherited standard commands are checked by tests
        inherited = {c.name: c for c in t.commands if c.loc.line == 0}
        self.duplicates(own, lambda c: c.name, "command", where=f" in subsystem type '{t.name}'")
        for c in own:
            if c.name in inherited:
                self.sink.error("RG1101", f"command '{c.name}' is already defined by '{t.extends}'",
                                c.at("name"), "give it another name; inherited commands cannot be replaced")
        n = self.facts.seq_bound("rapid::SubsystemType", "commands")
        if n is not None and len(t.commands) > n:
            extra = t.commands[n]
            self.sink.error("RG1107", f"subsystem type '{t.name}' has {len(t.commands)} commands; "
                            f"SubsystemType.commands holds at most {n}",
                            extra.at("name") if extra.loc.line else t.at("name"),
                            "split the commands over more subsystem types")
        for c in own:
            self.command(c)

    def command(self, c: CommandSpec) -> None:
        self.bound(c.name, c.at("name"), "command name", "rapid::CommandDef", "name")
        self.duplicates(c.parameters, lambda p: p.name, "parameter", where=f" in command '{c.name}'")
        # a command's arguments travel in Command.arguments, its parameters in CommandDef.parameters
        bounds = [(n, f"{s.split('::')[-1]}.{m} ({self._seq_name(s, m)})")
                  for s, m in (("rapid::Command", "arguments"), ("rapid::CommandDef", "parameters"))
                  if (n := self.facts.seq_bound(s, m)) is not None]
        if bounds and len(c.parameters) > min(bounds)[0]:
            n, where = min(bounds)
            self.sink.error("RG1107", f"command '{c.name}' has {len(c.parameters)} parameters; "
                            f"{where} holds at most {n}", c.parameters[n].loc,
                            "pass related values together (RAPID_VEC3d, RAPID_MAT33f) or split the command")
        for p in c.parameters:
            self.bound(p.name, p.at("name"), "parameter name", "rapid::KeyTypePair", "key")
            self.values.check(p, "parameter")

    def _seq_name(self, struct: str, member: str) -> str:
        decl = self.facts.struct(struct)
        for m in decl.members if decl else ():
            if m.name == member:
                return str(m.type).split("::")[-1]
        return "a sequence"

    # -- subsystems -------------------------------------------------------------------------
    def subsystems(self) -> None:
        spec = self.spec
        subs = self.loaded.subsystems
        self.duplicates(spec.subsystems, lambda s: s.name, "subsystem")  # the native one: native()
        types = self.loaded.types
        for s in spec.subsystems:
            self.bound(s.name, s.at("name"), "subsystem name", "rapid::Subsystem", "name")
            if s.type not in types:
                where = s.at("type") if s.has("type") else s.at("name")
                msg = (f"unknown subsystem type '{s.type}'" if s.has("type") else
                       f"subsystem '{s.name}' has no 'type' and is not a standard subsystem")
                self.sink.error("RG1102", msg, where, did_you_mean(s.type, types) or
                                f"define it under subsystem_types, or use a standard type: {', '.join(STANDARD_TYPES)}")
        n = self.facts.seq_bound("rapid::CommandConfig", "availableSubsystems")
        if n is not None and len(subs) > n:
            self.sink.error("RG1107", f"{len(subs)} subsystems; CommandConfig.availableSubsystems holds at most {n}",
                            subs[n].loc, "merge subsystems of the same type")
        used = self.loaded.used_types
        n = self.facts.seq_bound("rapid::CommandConfig", "availableSubsystemTypes")
        if n is not None and len(used) > n:
            self.sink.error("RG1107", f"{len(used)} subsystem types in use; CommandConfig.availableSubsystemTypes "
                            f"holds at most {n}", used[n].loc, "share types between subsystems")
        for t in spec.subsystem_types:
            if t.name in types and types[t.name] not in used and t.name not in STANDARD_TYPES:
                self.sink.warning("RG1108", f"subsystem type '{t.name}' has no subsystem", t.at("name"),
                                  f"add '- {{name: ..., type: {t.name}}}' under subsystems, or remove it")

    def native(self) -> None:
        n = self.spec.native
        if n is None:
            return
        self.bound(n.subsystem, n.at("subsystem"), "native subsystem name", "rapid::Subsystem", "name")
        self.bound(n.command, n.at("command"), "native command name", "rapid::CommandDef", "name")
        self.bound(n.parameter, n.at("parameter"), "native parameter name", "rapid::KeyTypePair", "key")
        # The passthrough adds a subsystem and a subsystem type, both named n.subsystem: one
        # error for a name that clashes with either or both.
        taken = []
        sub = next((s for s in self.spec.subsystems if s.name == n.subsystem), None)
        if sub is not None:
            taken.append(f"a subsystem (line {sub.loc.line})")
        if n.subsystem in STANDARD_TYPES:
            taken.append("a standard subsystem type")
        elif any(t.name == n.subsystem for t in self.spec.subsystem_types):
            taken.append("a subsystem type")
        if taken:
            self.sink.error("RG1101", f"native subsystem '{n.subsystem}' is also the name of {' and of '.join(taken)}",
                            n.at("subsystem"), "the passthrough adds a subsystem and a subsystem type of that name; "
                            "pick another for native.subsystem (default 'Native')")

    # -- access control -----------------------------------------------------------------------
    def access_control(self) -> None:
        ac = self.spec.access_control
        if ac is None:
            return
        rules = ac.rules
        self.duplicates(rules, lambda r: r.source, "command source", "source")
        subs: dict[str, SubsystemSpec] = {}
        for s in self.loaded.subsystems:  # descriptor order (hints list them); first wins on duplicates
            subs.setdefault(s.name, s)
        types = self.loaded.types
        all_cmds = sorted({c.name for s in subs.values() if s.type in types for c in types[s.type].commands})
        for r in rules:
            self.bound(r.source, r.at("source"), "command source", "rapid::Command", "cmdSrc")
            for i, pattern in enumerate(r.allow):
                self.pattern(pattern, r, i, subs, types, all_cmds)

    def pattern(self, pattern: str, rule: Located, i: int, subs, types, all_cmds) -> None:
        loc = rule.at("allow", i)
        if pattern == "*":
            return
        sub, sep, cmd = pattern.partition("/")
        if not sep or not sub or not cmd or "/" in cmd:
            self.sink.error("RG1402", f"access pattern '{pattern}' is not 'Subsystem/command'", loc,
                            "write 'LeftArm/Open the Hand', 'LeftArm/*', '*/stopAllMotion' or '*'")
            return
        if sub != "*" and sub not in subs:
            self.sink.error("RG1103", f"unknown subsystem '{sub}' in access pattern", loc,
                            did_you_mean(sub, subs) or f"subsystems: {', '.join(subs) or 'none'}")
            return
        if cmd == "*":
            return
        names = all_cmds if sub == "*" else [c.name for c in types[subs[sub].type].commands] \
            if subs[sub].type in types else []
        if cmd not in names:
            msg = f"no subsystem has a command '{cmd}'" if sub == "*" else f"subsystem '{sub}' has no command '{cmd}'"
            self.sink.error("RG1104", msg, loc,
                            did_you_mean(cmd, names) or f"its commands: {', '.join(names) or 'none'}")


def check_asset(loaded: "LoadedAsset", sink: DiagnosticSink) -> None:
    Checker(loaded, sink).run()
