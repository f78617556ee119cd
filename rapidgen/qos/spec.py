"""The neutral QoS library (specs/qos/rapid.yaml): loading, checks, inheritance.

    from rapidgen.qos import default_library, load_qos
    spec = default_library()                    # the library the package ships
    spec = load_qos("site-qos.yaml", sink)      # another one; None after diagnostics
    writer, reader = spec.effective("RapidConfigQos")

Every problem is a located diagnostic (RG16xx) pointing into the YAML. `effective()`
resolves a profile's base chain and fills what no profile sets with the DDS
specification's defaults, so every vendor's output states the same QoS.
"""
from __future__ import annotations

import dataclasses
import fnmatch
import functools
import json
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

from rapidgen.diagnostics import DiagnosticSink, SourceLoc, did_you_mean
from rapidgen.packagedata import read_text

if TYPE_CHECKING:
    import jsonschema

    from rapidgen.yamlread import YamlDoc

MAX_BYTES = 1024 * 1024
PACKAGED = "rapidgen/qos/rapid.yaml"  # how diagnostics name the packaged library


@dataclass(frozen=True, slots=True)
class History:
    kind: str  # keep_last | keep_all
    depth: int | None = None  # keep_last only


@dataclass(frozen=True, slots=True)
class Policies:
    """What one profile declares for one side (None: not declared here)."""

    reliability: str | None = None  # reliable | best_effort
    durability: str | None = None  # volatile | transient_local
    history: History | None = None
    publish_mode: str | None = None  # writers: synchronous | asynchronous

    def over(self, below: "Policies") -> "Policies":
        """These policies with `below` filling the gaps."""
        return Policies(self.reliability or below.reliability, self.durability or below.durability,
                        self.history or below.history, self.publish_mode or below.publish_mode)

    @property
    def empty(self) -> bool:
        return self == Policies()


@dataclass(frozen=True, slots=True)
class Ports:
    base: int
    domain_gain: int
    participant_gain: int
    d0: int  # discovery multicast
    d1: int  # discovery unicast
    d2: int  # user multicast
    d3: int  # user unicast

    def discovery_unicast(self, domain: int, index: int) -> int:
        return self.base + self.domain_gain * domain + self.d1 + self.participant_gain * index

    def user_unicast(self, domain: int, index: int) -> int:
        return self.base + self.domain_gain * domain + self.d3 + self.participant_gain * index


@dataclass(frozen=True, slots=True)
class Participant:
    type_information: bool | None = None
    max_message_size: int | None = None
    ports: Ports | None = None

    def over(self, below: "Participant") -> "Participant":
        return Participant(below.type_information if self.type_information is None else self.type_information,
                           self.max_message_size or below.max_message_size, self.ports or below.ports)


@dataclass(frozen=True, slots=True)
class Profile:
    name: str
    base: str | None
    description: str
    both: Policies  # reliability/durability/history written at the profile level
    writer: Policies
    reader: Policies
    participant: Participant
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class TopicRule:
    pattern: str
    profile: str
    loc: SourceLoc

    def matches(self, type_name: str) -> bool:
        return fnmatch.fnmatchcase(type_name, self.pattern.replace("[", "[[]"))


@dataclass(frozen=True, slots=True)
class DiscoveryServer:
    address: str
    port: int
    id: int = 0

    @property
    def prefix(self) -> str:
        """Fast DDS's GUID prefix for server `id` (as `fastdds discovery -i id` uses)."""
        return f"44.53.{self.id:02x}.5f.45.50.52.4f.53.49.4d.41"


@dataclass(frozen=True, slots=True)
class Tcp:
    discovery_server: DiscoveryServer
    listening_port: int = 0


@dataclass(frozen=True, slots=True)
class Transport:
    name: str
    description: str = ""
    default: bool = False
    interfaces: tuple[str, ...] = ()
    multicast: bool = True
    multicast_address: str | None = None
    peers: tuple[str, ...] = ()
    max_participants_per_host: int | None = None
    tcp: Tcp | None = None
    rtt: float | None = None  # s, the link's round trip: reliability timers follow it (docs/qos.md)
    lease: float | None = None  # s a silent participant keeps its matches (the longest outage ridden through)


# What a profile gets for a policy that no profile in its chain sets (DDS 1.4, 2.2.3).
DDS_DEFAULT_WRITER = Policies("reliable", "volatile", History("keep_last", 1), "synchronous")
DDS_DEFAULT_READER = Policies("best_effort", "volatile", History("keep_last", 1), None)


@dataclass(frozen=True, slots=True)
class QosSpec:
    file: str
    library: str
    profiles: tuple[Profile, ...]  # bases before the profiles naming them, else as written
    topics: tuple[TopicRule, ...]
    partition: str | None
    transports: tuple[Transport, ...]

    def profile(self, name: str) -> Profile:
        for p in self.profiles:
            if p.name == name:
                return p
        raise KeyError(name)

    def has_profile(self, name: str) -> bool:
        return any(p.name == name for p in self.profiles)

    def chain(self, name: str) -> list[Profile]:
        """The profile, then its base, its base's base, ..."""
        out, seen = [], set()
        current: str | None = name
        while current is not None and current not in seen:
            seen.add(current)
            p = self.profile(current)
            out.append(p)
            current = p.base
        return out

    def effective(self, name: str) -> tuple[Policies, Policies]:
        """(writer, reader) QoS of a profile: its chain resolved, gaps at DDS defaults."""
        writer, reader = Policies(), Policies()
        for p in self.chain(name):
            writer = writer.over(p.writer).over(p.both)
            reader = reader.over(p.reader).over(p.both)
        return writer.over(DDS_DEFAULT_WRITER), reader.over(DDS_DEFAULT_READER)

    def participant(self, name: str) -> Participant:
        out = Participant()
        for p in self.chain(name):
            out = out.over(p.participant)
        return out

    def profile_for_type(self, type_name: str) -> str | None:
        for rule in self.topics:
            if rule.matches(type_name):
                return rule.profile
        return None

    @property
    def default_profile(self) -> Profile:
        """The root of the inheritance tree that most profiles share (RapidDefaultQos)."""
        roots = [p for p in self.profiles if p.base is None]
        return max(roots, key=lambda r: sum(1 for p in self.profiles if self.chain(p.name)[-1] is r))

    @property
    def default_transport(self) -> Transport:
        return next(t for t in self.transports if t.default)

    def transport(self, name: str) -> Transport:
        return next(t for t in self.transports if t.name == name)


# ---------------------------------------------------------------- loading


@functools.lru_cache(maxsize=1)
def _validator() -> jsonschema.Draft202012Validator:
    import jsonschema  # only where a library is schema-checked (~0.05 s of imports)
    return jsonschema.Draft202012Validator(schema())


@functools.lru_cache(maxsize=1)
def schema() -> dict:
    return json.loads(read_text("rapidgen.qos", "qos.schema.json"))


@functools.lru_cache(maxsize=1)
def default_library() -> QosSpec:
    """The library the package ships; a broken one is a packaging bug. Its schema check is
    tests/qos/test_spec.py's, not every run's (the file is part of the package); the
    semantic checks still run.

    Parsed on each run that needs it: a precomputed form saved about 1.5% of a `generate`
    with the qos target (bench/codegen.py --devices), below the tenth a speed device must
    pay to be kept (docs/ci.md, "Speed"), and was removed."""
    return _parse_packaged(_packaged_text())


def _packaged_text() -> str:
    return read_text("rapidgen.qos", "rapid.yaml")


def _parse_packaged(text: str) -> QosSpec:
    sink = DiagnosticSink()
    spec = parse_qos(text, PACKAGED, sink, schema_checked=True)
    if spec is None:
        raise RuntimeError(f"the packaged QoS library is invalid: {sink.diagnostics[0]}")
    return spec


def load_qos(path: str, sink: DiagnosticSink) -> QosSpec | None:
    here = SourceLoc(path, 1, 1)
    try:
        with open(path, "rb") as fh:
            data = fh.read(MAX_BYTES + 1)
    except OSError as exc:
        sink.error("RG1601", f"cannot read QoS library '{path}': {exc.strerror or exc}", here)
        return None
    if len(data) > MAX_BYTES or b"\0" in data:
        sink.error("RG1601", f"'{path}' is not a QoS library (binary or over 1 MiB)", here)
        return None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        sink.error("RG1601", f"'{path}' is not valid UTF-8 (byte {exc.start})", here)
        return None
    return parse_qos(text, path, sink)


def parse_qos(text: str, file: str, sink: DiagnosticSink, schema_checked: bool = False) -> QosSpec | None:
    """`schema_checked`: the text is known to pass the schema (the packaged library)."""
    from rapidgen.yamlread import parse_yaml  # PyYAML: only where a library is parsed

    doc = parse_yaml(text.lstrip("\ufeff"), file, sink)
    if doc is None:
        return None
    if doc.data is None:
        sink.error("RG1602", "the QoS library is empty", doc.loc(()), "start with 'version: 1'")
        return None
    if not schema_checked and not _schema_ok(doc, sink):
        return None
    spec = _build(doc)
    if not _check(spec, doc, sink):
        return None
    return dataclasses.replace(spec, profiles=tuple(ordered(spec)))


def _schema_ok(doc: YamlDoc, sink: DiagnosticSink) -> bool:
    from rapidgen.schema_report import end_of, report_capped  # imports jsonschema
    return not report_capped(_validator().iter_errors(doc.data), sink, lambda e: _translated(e, doc),
                             end_of(doc), "RG1602")


_TYPES = {"object": "a mapping", "array": "a list", "string": "a string", "boolean": "true or false",
          "integer": "a whole number", "number": "a number"}


def _translated(err: jsonschema.ValidationError, doc: YamlDoc) -> list[tuple]:
    """_schema_error's diagnostics as (code, message, loc, hint), for report_capped."""
    local = DiagnosticSink()
    _schema_error(err, doc, local)
    return [(d.code, d.message, d.loc, d.hint) for d in local.diagnostics]


def _clip(value: object, limit: int = 40) -> str:
    text = str(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


def _schema_error(err: jsonschema.ValidationError, doc: YamlDoc, sink: DiagnosticSink) -> None:
    path = tuple(err.absolute_path)
    where = ".".join(str(p) for p in path) or "the QoS library"
    v = err.validator
    # (err.schema and err.validator_value are typed loosely: a schema may be a bool)
    if v == "additionalProperties" and isinstance(err.instance, dict):
        allowed = sorted(err.schema.get("properties", {})) if isinstance(err.schema, Mapping) else []
        for key in sorted(k for k in err.instance if k not in allowed):
            sink.error("RG1602", f"unknown key '{_clip(key)}' in {where}", doc.key_loc(path + (key,)),
                       did_you_mean(key, allowed) or (f"expected one of: {', '.join(allowed)}" if allowed else None))
        return
    if v == "required":
        missing = [k for k in _items(err.validator_value) if isinstance(err.instance, dict) and k not in err.instance]
        msg = f"{where}: missing key '{missing[0]}'" if missing else f"{where}: missing key"
    elif v == "enum":
        msg = f"{where}: '{_clip(err.instance)}' is not one of {', '.join(map(str, _items(err.validator_value)))}"
    elif v == "const":
        msg = f"{where}: must be {err.validator_value!r}"
    elif v == "type":
        msg = f"{where}: expected {_TYPES.get(str(err.validator_value), err.validator_value)}"
    elif v in ("minimum", "maximum"):
        msg = f"{where}: {err.instance} is {'below the minimum' if v == 'minimum' else 'above the maximum'} {err.validator_value}"
    elif v == "pattern":
        msg = f"{where}: '{_clip(err.instance)}' is not a valid name or address"
    elif v == "not" and path and path[-1:] != () and isinstance(err.instance, dict) and "depth" in err.instance:
        msg = f"{where}: keep_all history takes no depth"
    elif v == "uniqueItems":
        msg = f"{where}: duplicate entries"
    else:
        msg = f"{where}: {err.message if len(err.message) < 120 else err.message[:117] + '...'}"
    sink.error("RG1602", msg, doc.loc(path))


def _items(value: object) -> list:
    """A schema keyword's list value (required, enum)."""
    return list(value) if isinstance(value, (list, tuple)) else []


def _history(d: dict | None) -> History | None:
    return None if d is None else History(d["kind"], d.get("depth"))


def _policies(d: dict | None) -> Policies:
    d = d or {}
    return Policies(d.get("reliability"), d.get("durability"), _history(d.get("history")), d.get("publish_mode"))


def _build(doc: YamlDoc) -> QosSpec:
    data = doc.data
    assert isinstance(data, dict)  # validated: the schema's top level is an object
    profiles = []
    for name, p in data["profiles"].items():
        part = p.get("participant") or {}
        ports = Ports(**part["ports"]) if "ports" in part else None
        profiles.append(Profile(
            name, p.get("base"), p.get("description", ""), _policies(p), _policies(p.get("writer")),
            _policies(p.get("reader")), Participant(part.get("type_information"), part.get("max_message_size"), ports),
            doc.key_loc(("profiles", name))))
    topics = tuple(TopicRule(t["type"], t["profile"], doc.loc(("topics", i))) for i, t in enumerate(data["topics"]))
    transports = []
    for name, t in data["transports"].items():
        tcp = None
        if "tcp" in t:
            ds = t["tcp"]["discovery_server"]
            tcp = Tcp(DiscoveryServer(ds["address"], ds["port"], ds.get("id", 0)), t["tcp"].get("listening_port", 0))
        transports.append(Transport(name, t.get("description", ""), t.get("default", False),
                                    tuple(t.get("interfaces", ())), t.get("multicast", True),
                                    t.get("multicast_address"), tuple(t.get("peers", ())),
                                    t.get("max_participants_per_host"), tcp, t.get("rtt"), t.get("lease")))
    return QosSpec(doc.file, data["library"], tuple(profiles), topics, data.get("partition"), tuple(transports))


def _check(spec: QosSpec, doc: YamlDoc, sink: DiagnosticSink) -> bool:
    ok = True
    names = [p.name for p in spec.profiles]
    for p in spec.profiles:
        if p.base is not None and p.base not in names:
            sink.error("RG1603", f"profile '{p.name}': unknown base profile '{p.base}'",
                       doc.loc(("profiles", p.name, "base")), did_you_mean(p.base, names))
            ok = False
    if ok:
        for p in spec.profiles:
            seen, current = [p.name], p.base
            while current is not None:
                if current in seen:
                    if current == p.name:
                        sink.error("RG1604", f"profile '{p.name}' inherits from itself: {' -> '.join(seen + [current])}",
                                   doc.loc(("profiles", p.name, "base")), "remove one 'base' of the cycle")
                        ok = False
                    break
                seen.append(current)
                current = spec.profile(current).base
    for i, rule in enumerate(spec.topics):
        if rule.profile not in names:
            sink.error("RG1605", f"unknown profile '{rule.profile}' for type '{rule.pattern}'",
                       doc.loc(("topics", i, "profile")), did_you_mean(rule.profile, names))
            ok = False
    defaults = [t.name for t in spec.transports if t.default]
    if len(defaults) != 1:
        loc = doc.loc(("transports", defaults[1], "default")) if len(defaults) > 1 else doc.key_loc(("transports",))
        sink.error("RG1606", f"{'more than one' if defaults else 'no'} default transport"
                   + (f" ({', '.join(defaults)})" if defaults else ""), loc,
                   "mark exactly one transport with 'default: true'")
        ok = False
    for t in spec.transports:
        if t.multicast_address and not t.multicast:
            sink.warning("RG1607", f"transport '{t.name}': multicast_address is unused with multicast: false",
                         doc.loc(("transports", t.name, "multicast_address")))
    return ok


def ordered(spec: QosSpec) -> list[Profile]:
    """Profiles with every base before the profiles naming it; otherwise as written."""
    out: list[Profile] = []
    placed: set[str] = set()
    pending = list(spec.profiles)
    while pending:
        for p in pending:
            if p.base is None or p.base in placed:
                out.append(p)
                placed.add(p.name)
                pending.remove(p)
                break
    return out


