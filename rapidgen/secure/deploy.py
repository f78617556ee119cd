"""The deployment file of `rapidgen secure`: which assets run (their descriptors) and which
ground tools exist, by source name, and which assets each may command or watch.

    version: 1
    assets: [../specs/assets/k10.yaml]     # descriptors, relative to this file
    domains: [1]                           # optional: the DDS domains granted (default: each asset's)
    validity_days: 365                     # optional: certificates issued by this run
    ground:
      - source: RapidWorkbench             # Command.cmdSrc; its participant's name in the keystore
        command: [K10Red]                  # asset names, or "*": every asset whose access_control admits it
        watch: ["*"]                       # assets whose configs, telemetry and acks it may read
        audit: [K10Red]                    # assets whose commands (anyone's) it may read too:
                                           # rapidgen conform, a recorder

Every problem is a located error (file:line:col, a hint). Commanding is granted only when
the asset's own access_control admits the source: the descriptor and the permissions agree
by construction (`Deployment.commands`).
"""
from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from typing import TypeGuard

from rapidgen.asset.resolved import LoadedAsset
from rapidgen.yamlread import YamlDoc, load_yaml
from rapidgen.diagnostics import DiagnosticSink, Severity, SourceLoc, did_you_mean
from rapidgen.diagnostics import display_path

NAME = re.compile(r"[A-Za-z0-9_.-]{1,64}\Z")  # a file name and a certificate CN, never a path


def plain_name(name: object) -> TypeGuard[str]:
    """A name that is one folder of the keystore and a certificate CN: 1-64 of A-Z a-z 0-9
    _ . - and not dots only ("." and ".." are the folder itself and its parent)."""
    return isinstance(name, str) and NAME.match(name) is not None and name.strip(".") != ""
TOP_KEYS = ("version", "assets", "domains", "validity_days", "ground")
TOOL_KEYS = ("source", "command", "watch", "audit", "description")
MAX_DOMAIN = 230  # what both DDS Security implementations parse in governance and permissions


@dataclass(frozen=True)
class Tool:
    source: str
    command: tuple[str, ...]  # asset names granted (after "*" and the access lists)
    watch: tuple[str, ...]  # asset names it may read (commanded and audited ones included)
    loc: SourceLoc
    audit: tuple[str, ...] = ()  # asset names whose command topic it may read


@dataclass
class Deployment:
    file: str
    assets: dict[str, LoadedAsset] = field(default_factory=dict)  # by asset name, file order
    tools: list[Tool] = field(default_factory=list)
    domains: tuple[int, ...] | None = None
    validity_days: int = 365

    def domains_of(self, asset: LoadedAsset) -> tuple[int, ...]:
        return self.domains if self.domains is not None else (asset.spec.domain,)

    def names(self) -> list[str]:
        """Every participant of the keystore: assets, then ground tools."""
        return [*self.assets, *(t.source for t in self.tools)]


def partition_of(asset: LoadedAsset) -> str:
    return asset.spec.partition or asset.spec.name


def admits(asset: LoadedAsset, source: str) -> bool:
    """Whether the descriptor's access_control lets `source` send it any command (the rule
    of runtime/rapid_runtime/access.py: no section admits everyone; an unlisted source gets
    the default)."""
    spec = asset.access
    if spec is None:
        return True
    rules = [r for r in spec.rules if r.source == source]
    if not rules:
        return spec.default == "allow"
    return any(r.allow for r in rules)


def _err(sink: DiagnosticSink, code: str, message: str, loc: SourceLoc, hint: str | None = None) -> None:
    sink.error(code, message, loc, hint)


class _Reader:
    def __init__(self, doc: YamlDoc, sink: DiagnosticSink) -> None:
        self.doc, self.sink = doc, sink

    def err(self, path: tuple, message: str, hint: str | None = None, key: bool = False) -> None:
        _err(self.sink, "RG2001", message, self.doc.key_loc(path) if key else self.doc.loc(path), hint)

    def keys(self, value: object, path: tuple, allowed: tuple[str, ...]) -> bool:
        if not isinstance(value, dict):
            self.err(path, "expected a mapping", f"keys: {', '.join(allowed)}")
            return False
        for k in value:
            if k not in allowed:
                self.err((*path, k), f"unknown key '{k}'", did_you_mean(str(k), allowed) or
                         f"known keys: {', '.join(allowed)}", key=True)
        return True

    def names(self, value: object, path: tuple, what: str) -> list[tuple[str, tuple]]:
        if value is None:
            return []
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            self.err(path, f"{what} must be a list of names", 'e.g. [K10Red] or ["*"]')
            return []
        return [(v, (*path, i)) for i, v in enumerate(value)]


def load_deployment(path: str, sink: DiagnosticSink, load_asset) -> Deployment | None:
    """The checked deployment, or None after errors (in the sink). `load_asset(path, sink)`
    loads a descriptor (rapidgen.asset.load.load_asset; a parameter to keep this module light)."""
    shown = display_path(path)
    doc = load_yaml(path, shown, sink)
    if doc is None:
        return None
    r = _Reader(doc, sink)
    data = doc.data
    if not r.keys(data, (), TOP_KEYS):
        return None
    assert isinstance(data, dict)
    dep = Deployment(shown)
    if data.get("version") != 1:
        r.err(("version",), "version must be 1", "the first line of a deployment file: version: 1")
    _read_settings(r, data, dep)
    base = os.path.dirname(path)
    for name, p in r.names(data.get("assets"), ("assets",), "assets"):
        sub = DiagnosticSink()
        loaded = load_asset(os.path.join(base, name), sub)
        sink.extend(d for d in sub.diagnostics if d.severity is not Severity.ERROR)
        if loaded is None or sub.has_errors:
            sink.diagnostics.extend(sub.errors)
            r.err(p, f"the descriptor '{name}' has errors (above)", "rapidgen validate it")
            continue
        asset_name = loaded.spec.name
        if not plain_name(asset_name):
            r.err(p, f"asset name {asset_name!r} is not a plain name (1-64 of A-Z a-z 0-9 _ . -, not dots only)",
                  "the name is also its folder and certificate name in the keystore")
            continue
        if any(ch in partition_of(loaded) for ch in "*?[]\\"):
            r.err(p, f"{asset_name}'s partition '{partition_of(loaded)}' holds a DDS wildcard (* ? [ ] \\)",
                  "DDS Security reads partitions in permissions as patterns: a grant for it would cover other "
                  "partitions; name the partition without them (dds.partition)")
            continue
        if dep.domains is None and loaded.spec.domain > MAX_DOMAIN:
            r.err(p, f"{asset_name}'s DDS domain {loaded.spec.domain} is above {MAX_DOMAIN}",
                  f"Cyclone's security plugins take domain ids 0..{MAX_DOMAIN}; grant others with domains: [...]")
            continue
        if asset_name in dep.assets:
            r.err(p, f"asset '{asset_name}' is listed twice", "each asset once")
            continue
        other = next((a for a in dep.assets.values() if partition_of(a) == partition_of(loaded) and
                      set(dep.domains_of(a)) & set(dep.domains_of(loaded))), None)
        if other is not None:
            shared = sorted(set(dep.domains_of(other)) & set(dep.domains_of(loaded)))
            r.sink.error("RG2002", f"{asset_name} uses partition '{partition_of(loaded)}', which is "
                         f"{other.spec.name}'s, on domain {', '.join(map(str, shared))}",
                         r.doc.loc(p), f"a grant in that partition would cover {other.spec.name}'s commands, acks "
                         f"and configs too: give {asset_name} a partition of its own (dds.partition in "
                         f"{display_path(loaded.spec.file)}), or another domain")
            continue
        dep.assets[asset_name] = loaded
    if not dep.assets and not sink.has_errors:
        r.err(("assets",) if "assets" in data else (), "no assets", "assets: [path/to/asset.yaml, ...]")
    _read_tools(r, data.get("ground"), dep)
    return None if sink.has_errors else dep


def _read_settings(r: _Reader, data: dict, dep: Deployment) -> None:
    if "domains" in data:
        doms = data["domains"]
        if not isinstance(doms, list) or not doms or not all(
                isinstance(d, int) and not isinstance(d, bool) and 0 <= d <= MAX_DOMAIN for d in doms):
            r.err(("domains",), f"domains must be a non-empty list of DDS domain ids (0..{MAX_DOMAIN})",
                  "leave it out to grant each asset's dds.domain")
        else:
            dep.domains = tuple(sorted(set(doms)))
    if "validity_days" in data:
        days = data["validity_days"]
        if not isinstance(days, int) or isinstance(days, bool) or not 1 <= days <= 3650:
            r.err(("validity_days",), "validity_days must be a whole number of days, 1..3650",
                  "certificates are re-issued before they expire (rapidgen secure --check warns)")
        else:
            dep.validity_days = days


def _read_tools(r: _Reader, tools: object, dep: Deployment) -> None:
    if tools is None:
        return
    if not isinstance(tools, list):
        r.err(("ground",), "ground must be a list of tools", "- {source: RapidWorkbench, command: [K10Red]}")
        return
    seen: set[str] = set()
    for i, entry in enumerate(tools):
        path = ("ground", i)
        if not r.keys(entry, path, TOOL_KEYS):
            continue
        assert isinstance(entry, dict)
        source = entry.get("source")
        if not plain_name(source):
            r.err((*path, "source") if "source" in entry else path,
                  "a ground tool needs a source: its Command.cmdSrc, 1-64 of A-Z a-z 0-9 _ . -, not dots only",
                  "the name is also its folder and certificate name in the keystore: a plain name, no slash, "
                  "no control character, not '.' or '..'")
            continue
        if source in seen or source in dep.assets:
            r.err((*path, "source"), f"'{source}' names two participants",
                  "every asset and ground tool needs its own name")
            continue
        seen.add(source)
        command = _targets(r, dep, source, entry.get("command"), (*path, "command"), commanding=True)
        watch = _targets(r, dep, source, entry.get("watch"), (*path, "watch"), commanding=False)
        audit = [a for a in _targets(r, dep, source, entry.get("audit"), (*path, "audit"), commanding=False)
                 if dep.assets[a].command_topic]
        watch = [a for a in dep.assets if a in watch or a in command or a in audit]
        dep.tools.append(Tool(source, tuple(command), tuple(watch), r.doc.loc(path), tuple(audit)))


def _targets(r: _Reader, dep: Deployment, source: str, value: object, path: tuple, commanding: bool) -> list[str]:
    out: list[str] = []
    for name, p in r.names(value, path, path[-1]):
        if name == "*":
            pool = [a for a, loaded in dep.assets.items() if not commanding or
                    (loaded.command_topic and admits(loaded, source))]
        elif name not in dep.assets:
            r.err(p, f"no asset '{name}' in this deployment", did_you_mean(name, dep.assets) or
                  f"assets: {', '.join(dep.assets) or '(none)'}")
            continue
        else:
            pool = [name]
            loaded = dep.assets[name]
            if commanding and not loaded.command_topic:
                r.err(p, f"'{name}' takes no commands (no subsystems)", "list it under watch")
                continue
            if commanding and not admits(loaded, source):
                r.err(p, f"{name}'s access_control does not admit source '{source}'",
                      f"add {{source: {source}, allow: [...]}} to {display_path(loaded.spec.file)}'s "
                      "access_control, or move it to watch")
                continue
        out.extend(a for a in pool if a not in out)
    return [a for a in dep.assets if a in out]
