"""QoS spec (+ asset) -> view objects for each vendor's template.

Everything a template prints is decided here: vendor enum spellings, which elements
appear (precomputed booleans and lists), locators, port numbers, profile names.
"""
from __future__ import annotations

import ipaddress

from dataclasses import dataclass

from rapidgen.qos.spec import Participant, Policies, Ports, QosSpec, Transport

# Bytes left for RTPS headers and inline QoS when Cyclone cuts samples into fragments.
FRAGMENT_HEADROOM = 150
FASTDDS_DEFAULT_MULTICAST = "239.255.0.1"

_OMG = {  # DDS-XML and RTI spell the enumerators the same way
    "reliable": "RELIABLE_RELIABILITY_QOS", "best_effort": "BEST_EFFORT_RELIABILITY_QOS",
    "volatile": "VOLATILE_DURABILITY_QOS", "transient_local": "TRANSIENT_LOCAL_DURABILITY_QOS",
    "keep_last": "KEEP_LAST_HISTORY_QOS", "keep_all": "KEEP_ALL_HISTORY_QOS",
    "asynchronous": "ASYNCHRONOUS_PUBLISH_MODE_QOS", "synchronous": "SYNCHRONOUS_PUBLISH_MODE_QOS",
}
_FASTDDS = {
    "reliable": "RELIABLE", "best_effort": "BEST_EFFORT", "volatile": "VOLATILE",
    "transient_local": "TRANSIENT_LOCAL", "keep_last": "KEEP_LAST", "keep_all": "KEEP_ALL",
    "asynchronous": "ASYNCHRONOUS", "synchronous": "SYNCHRONOUS",
}


@dataclass(frozen=True)
class Limits:
    """Fast DDS ResourceLimitsQosPolicy of one endpoint (0: unlimited)."""

    max_samples: int
    max_instances: int
    max_samples_per_instance: int


@dataclass(frozen=True)
class Endpoint:
    """One side's QoS, spelt for one vendor; None: not written."""

    reliability: str | None
    durability: str | None
    history_kind: str | None
    history_depth: int | None
    publish_mode: str | None
    limits: Limits | None = None  # Fast DDS only

    @property
    def has_history(self) -> bool:
        return self.history_kind is not None

    @property
    def has_depth(self) -> bool:
        return self.history_depth is not None

    @property
    def empty(self) -> bool:
        return self == Endpoint(None, None, None, None, None)


def endpoint(p: Policies, names: dict[str, str], limits: Limits | None = None) -> Endpoint:
    return Endpoint(names.get(p.reliability or ""), names.get(p.durability or ""),
                    names.get(p.history.kind) if p.history else None,
                    p.history.depth if p.history else None, names.get(p.publish_mode or ""), limits)


# Fast DDS 2.9 defaults that do not fit RAPID (docs/qos.md, "Fast DDS: resource limits and
# publish mode"). Every RAPID message is keyed (Message.hdr; Ack also by cmdId, one instance
# per command), and Fast DDS keeps at most 10 instances per endpoint by default: an ack
# writer refuses the 11th command's acks, an ack reader drops them. So no instance limit;
# the applications bound instances instead (an asset unregisters the acks of old commands,
# a reader frees an unregistered instance once it has taken its samples).
FASTDDS_UNLIMITED = 0  # 0, not LENGTH_UNLIMITED (-1): a 2.9 writer history refuses every instance with -1
FASTDDS_KEEP_ALL_PER_INSTANCE = 400  # Fast DDS's own default; a keep-all writer blocks beyond it


def fastdds_limits(p: Policies) -> Limits:
    """No limit on instances or in total (Fast DDS refuses a finite max_samples with
    unlimited instances); per instance the history depth, or 400 samples for keep_all."""
    per = p.history.depth if p.history and p.history.kind == "keep_last" and p.history.depth else \
        FASTDDS_KEEP_ALL_PER_INSTANCE
    return Limits(FASTDDS_UNLIMITED, FASTDDS_UNLIMITED, per)


def fastdds_writer(p: Policies) -> Policies:
    """Reliable writers publish SYNCHRONOUS whatever the library says. Seen with Fast DDS
    2.9.1 in ASYNCHRONOUS mode: keep-last samples replaced before the sending thread sent
    them (each ack's EXECUTING overwritten at once by its COMPLETED) never reached a volatile
    Cyclone reader, 29 of 30 commands' acks lost for good (durable and Fast DDS readers got
    them; tests/cpp/test_fastdds_limits.py). Best-effort writers (telemetry, images) keep the
    library's mode: nothing is resent to them anyway."""
    if p.reliability != "reliable":
        return p
    return Policies(p.reliability, p.durability, p.history, "synchronous")


@dataclass(frozen=True)
class ProfileView:
    name: str
    key: str  # library::name
    base_key: str | None
    description: str
    writer: Endpoint
    reader: Endpoint
    partition: str | None
    rti_participant: "RtiParticipant | None" = None

    @property
    def has_base(self) -> bool:
        return self.base_key is not None

    @property
    def has_partition(self) -> bool:
        return self.partition is not None


def partition_of(spec: QosSpec, asset) -> str | None:
    if asset is None or spec.partition is None:
        return None
    name = asset.spec.partition or asset.spec.name
    return spec.partition.replace("{asset}", name)


def effective_profiles(spec: QosSpec, asset, names: dict[str, str], publish_mode: bool) -> list[ProfileView]:
    """Every profile with its whole chain resolved: Fast DDS (publish_mode True: the Fast DDS
    publish mode and resource limits above), DDS-XML (no publish mode)."""
    part = partition_of(spec, asset)
    out = []
    for p in spec.profiles:
        writer, reader = spec.effective(p.name)
        if publish_mode:
            w = endpoint(fastdds_writer(writer), names, fastdds_limits(writer))
            r = endpoint(reader, names, fastdds_limits(reader))
        else:
            w = endpoint(Policies(writer.reliability, writer.durability, writer.history, None), names)
            r = endpoint(reader, names)
        out.append(ProfileView(p.name, f"{spec.library}::{p.name}", f"{spec.library}::{p.base}" if p.base else None,
                               p.description, w, r, part))
    return out


# ---------------------------------------------------------------- RTI Connext


@dataclass(frozen=True)
class Property:
    name: str
    value: str


@dataclass(frozen=True)
class RtiParticipant:
    type_code_off: bool
    ports: Ports | None
    properties: tuple[Property, ...]
    builtin_mask: str | None
    initial_peers: tuple[str, ...]
    multicast_receive: tuple[str, ...]
    sets_discovery: bool  # write <discovery> (an empty multicast list disables multicast)

    @property
    def has_ports(self) -> bool:
        return self.ports is not None

    @property
    def has_properties(self) -> bool:
        return bool(self.properties)

    @property
    def has_mask(self) -> bool:
        return self.builtin_mask is not None

    @property
    def has_multicast_receive(self) -> bool:
        return bool(self.multicast_receive)


def _rti_message_size(part: Participant) -> tuple[Property, ...]:
    if part.max_message_size is None:
        return ()
    return (Property("dds.transport.UDPv4.builtin.parent.message_size_max", str(part.max_message_size)),)


def rti_profiles(spec: QosSpec, asset) -> list[ProfileView]:
    """RAPID's original form: each profile states only what it adds to its base."""
    part = partition_of(spec, asset)
    root = spec.default_profile.name
    out = []
    for p in spec.profiles:
        writer = endpoint(p.writer.over(p.both), _OMG)
        reader = endpoint(p.reader.over(p.both), _OMG)
        participant = None
        if p.participant != Participant():
            participant = RtiParticipant(p.participant.type_information is False, p.participant.ports,
                                         _rti_message_size(p.participant), None, (), (), False)
        out.append(ProfileView(p.name, f"{spec.library}::{p.name}", f"{spec.library}::{p.base}" if p.base else None,
                               p.description, writer, reader, part if p.name == root else None, participant))
    return out


def rti_transport_name(t: Transport) -> str:
    return "Rapid" + "".join(w.capitalize() for w in t.name.split("_")) + "TransportQos"


@dataclass(frozen=True)
class RtiTransport:
    name: str
    base_key: str
    description: str
    is_default: bool
    participant: RtiParticipant
    tcp_note: bool  # the transport also has a Fast DDS TCP variant RTI does not get


def rti_transports(spec: QosSpec) -> list[RtiTransport]:
    root = spec.default_profile
    size = _rti_message_size(spec.participant(root.name))
    out = []
    for t in spec.transports:
        props = list(size)
        if t.interfaces:
            props.append(Property("dds.transport.UDPv4.builtin.parent.allow_interfaces_list", ",".join(t.interfaces)))
        index = f"{t.max_participants_per_host - 1}@" if t.max_participants_per_host else ""
        if t.multicast:
            group = t.multicast_address or FASTDDS_DEFAULT_MULTICAST
            peers = tuple(f"builtin.udpv4://{a}" for a in (group, *t.peers))
            receive: tuple[str, ...] = (f"udpv4://{group}",)
        else:
            peers = tuple(f"{index}builtin.udpv4://{a}" for a in t.peers)
            receive = ()
        participant = RtiParticipant(False, None, tuple(props), "UDPv4", peers, receive, True)
        out.append(RtiTransport(rti_transport_name(t), f"{spec.library}::{root.name}", t.description, t.default,
                                participant, t.tcp is not None))
    return out


# ---------------------------------------------------------------- Cyclone DDS


@dataclass(frozen=True)
class CycloneView:
    name: str
    description: str
    interfaces: tuple[str, ...]
    allow_multicast: str
    spdp_multicast_address: str | None
    max_message_size: str | None
    fragment_size: str | None
    participant_index: str | None
    max_auto_participant_index: int | None
    peers: tuple[str, ...]
    ports: Ports | None
    lease: str | None = None  # Discovery/LeaseDuration
    spdp_interval: str | None = None  # Discovery/SPDPInterval
    heartbeat: str | None = None  # Internal/HeartbeatInterval (also its minsched)
    nack_repeat: str | None = None  # Internal/AutoReschedNackDelay

    @property
    def has_internal(self) -> bool:
        return self.heartbeat is not None

    @property
    def has_interfaces(self) -> bool:
        return bool(self.interfaces)

    @property
    def has_peers(self) -> bool:
        return bool(self.peers)


def cyclone_views(spec: QosSpec) -> list[CycloneView]:
    part = spec.participant(spec.default_profile.name)
    size = part.max_message_size
    out = []
    for t in spec.transports:
        unicast = not t.multicast
        out.append(CycloneView(
            t.name, t.description, t.interfaces, "true" if t.multicast else "false",
            t.multicast_address if t.multicast else None,
            f"{size}B" if size else None, f"{size - FRAGMENT_HEADROOM}B" if size else None,
            "auto" if unicast else None,
            (t.max_participants_per_host - 1) if unicast and t.max_participants_per_host else None,
            t.peers, part.ports, *_cyclone_link(t)))
    return out


def _ms(seconds: float) -> str:
    return f"{round(seconds * 1000)}ms"


def _cyclone_link(t: Transport) -> tuple[str | None, ...]:
    """(lease, SPDP interval, heartbeat, NACK repeat) for a transport with rtt/lease.
    Cyclone's defaults (heartbeat 100 ms, NACK repeat 3 s) suit a LAN; over a 2.6 s round
    trip a reader NACKs a lost sample at every heartbeat while the resend is on its way,
    and the writer resends for each: ~25 copies (measured, docs/field.md). A heartbeat per
    round trip asks once per round trip. Announcements every 2 round trips (at least 5 s,
    at most 30 s, and within the lease) so one lost announcement delays discovery little."""
    lease = _ms(t.lease) if t.lease else None
    if t.rtt is None:
        return lease, None, None, None
    spdp = min(max(5.0, 2 * t.rtt), 30.0, 0.8 * (t.lease or 10.0))
    return lease, _ms(spdp), _ms(t.rtt), _ms(2 * t.rtt)


# ---------------------------------------------------------------- Fast DDS


@dataclass(frozen=True)
class Locator:
    kind: str  # udpv4 | tcpv4
    address: str | None = None
    port: int | None = None  # TCP logical port
    physical_port: int | None = None

    @property
    def is_any(self) -> bool:
        return self.address is None


@dataclass(frozen=True)
class FastTransport:
    id: str
    type: str  # UDPv4 | TCPv4
    max_message_size: int | None
    interfaces: tuple[str, ...]
    max_initial_peers_range: int | None
    listening_ports: tuple[int, ...]

    @property
    def is_tcp(self) -> bool:
        return self.type == "TCPv4"


@dataclass(frozen=True)
class RemoteServer:
    prefix: str
    locator: Locator


@dataclass(frozen=True)
class FastParticipant:
    name: str
    description: str
    is_default: bool
    domain: int | None
    participant_name: str | None
    discovery: str  # SIMPLE | CLIENT | SERVER
    prefix: str | None
    servers: tuple[RemoteServer, ...]
    meta_unicast: tuple[Locator, ...]
    initial_peers: tuple[Locator, ...]
    default_unicast: tuple[Locator, ...]
    transport: str
    ports: Ports | None
    lease: Duration | None = None  # builtin/discovery_config/leaseDuration
    announcement: Duration | None = None  # .../leaseAnnouncement
    link: str | None = None  # property rapid.link: the endpoint profiles <profile>@<link> carry its timers

    @property
    def has_builtin(self) -> bool:
        return self.discovery != "SIMPLE" or bool(self.meta_unicast or self.initial_peers or self.lease)


@dataclass(frozen=True)
class Duration:
    """A Fast DDS XML duration (<sec>, <nanosec>)."""

    sec: int
    nanosec: int

    @classmethod
    def of(cls, seconds: float) -> "Duration":
        ns = round(seconds * 1e9)
        return cls(ns // 1_000_000_000, ns % 1_000_000_000)


@dataclass(frozen=True)
class FastLink:
    """Reliability timers of the endpoint profiles `<profile>@<transport>` for a transport
    with `rtt` (docs/qos.md "Slow links"): Fast DDS sets them per writer and reader, so each
    RAPID profile gets a copy per such transport; the C++ runtime picks the copy named by
    its participant's `rapid.link` property."""

    transport: str
    heartbeat: Duration  # writer times/heartbeatPeriod
    nack_suppression: Duration  # writer times/nackSupressionDuration
    max_blocking: Duration  # reliability max_blocking_time of writers


def _fast_lease(t: Transport) -> tuple[Duration | None, Duration | None]:
    """(leaseDuration, leaseAnnouncement) for a transport with lease and/or rtt. Fast DDS's
    defaults are 20 s and 3 s; announcements as Cyclone's SPDP interval (_cyclone_link):
    every 2 round trips, at least 5 s, at most 30 s and 0.8 x the lease. A lease alone keeps
    the 3 s announcement unless the lease is too short for it."""
    if t.rtt is None and t.lease is None:
        return None, None
    lease = t.lease or 20.0
    every = min(max(5.0, 2 * t.rtt), 30.0, 0.8 * lease) if t.rtt is not None else min(3.0, 0.8 * lease)
    return Duration.of(lease), Duration.of(every)


def fastdds_links(spec: QosSpec) -> list[FastLink]:
    """One per transport with `rtt`. The heartbeat once per round trip (Fast DDS's 3 s
    default is near the Moon's 2.6 s but 10x too slow for a 0.3 s relay): a reader NACKs only
    on a heartbeat, so a lost sample is asked for about once per round trip. NACKs for a
    sample that arrive within 0.8 round trip of its (re)send were sent before it could have
    arrived (the writer's default, 0, resends for each). A keep-all writer whose history is
    full waits for acknowledgements, which take a round trip: it blocks up to 2 round trips
    (default 100 ms) before write() fails."""
    return [FastLink(t.name, Duration.of(t.rtt), Duration.of(0.8 * t.rtt), Duration.of(2 * t.rtt))
            for t in spec.transports if t.rtt is not None]


def _is_loopback(interface: str) -> bool:
    try:
        return ipaddress.ip_address(interface).is_loopback
    except ValueError:  # an interface name
        return False


def _fast_udp(t: Transport, size: int | None) -> tuple[FastTransport, FastParticipant]:
    # Fast DDS 2.9's maxMessageSize is also its receive buffer: a datagram over it is
    # dropped. On a loopback-only transport nothing needs the cap (lo's MTU is 64 KiB) and
    # other same-host stacks send more (RustDDS 0.15: up to 64 KiB), so keep Fast DDS's default.
    if t.interfaces and all(_is_loopback(a) for a in t.interfaces):
        size = None
    tr = FastTransport(f"rapid_udp_{t.name}", "UDPv4", size, t.interfaces,
                       t.max_participants_per_host, ())
    meta: tuple[Locator, ...] = ()
    peers: tuple[Locator, ...] = ()
    if not t.multicast:  # a unicast metatraffic list alone means: no multicast listener
        meta = tuple(Locator("udpv4", a) for a in t.interfaces) or (Locator("udpv4"),)
        peers = tuple(Locator("udpv4", a) for a in t.peers)
    elif t.peers:
        peers = tuple(Locator("udpv4", a) for a in (t.multicast_address or FASTDDS_DEFAULT_MULTICAST, *t.peers))
    default_uc = tuple(Locator("udpv4", a) for a in t.interfaces)
    return tr, FastParticipant(f"rapid_{t.name}", t.description, t.default, None, None, "SIMPLE", None, (),
                               meta, peers, default_uc, tr.id, None, *_fast_lease(t),
                               t.name if t.rtt is not None else None)


def fastdds_view(spec: QosSpec, asset) -> tuple[list[FastTransport], list[FastParticipant]]:
    part = spec.participant(spec.default_profile.name)
    domain = asset.spec.domain if asset is not None else None
    pname = asset.spec.name if asset is not None else None
    transports: list[FastTransport] = []
    participants: list[FastParticipant] = []

    def add(tr: FastTransport, pa: FastParticipant) -> None:
        transports.append(tr)
        participants.append(FastParticipant(pa.name, pa.description, pa.is_default, domain, pname, pa.discovery,
                                            pa.prefix, pa.servers, pa.meta_unicast, pa.initial_peers,
                                            pa.default_unicast, pa.transport, part.ports, pa.lease,
                                            pa.announcement, pa.link))

    for t in spec.transports:
        add(*_fast_udp(t, part.max_message_size))
        if t.tcp is None:
            continue
        ds = t.tcp.discovery_server
        server_loc = Locator("tcpv4", ds.address, ds.port, ds.port)
        listen = (t.tcp.listening_port,) if t.tcp.listening_port else ()
        client = FastTransport(f"rapid_tcp_{t.name}", "TCPv4", None, t.interfaces, None, listen)
        add(client, FastParticipant(f"rapid_{t.name}_tcp", f"{t.name} over TCP: a client of the discovery server",
                                    False, None, None, "CLIENT", None, (RemoteServer(ds.prefix, server_loc),),
                                    (), (), (), client.id, None, *_fast_lease(t),
                                    t.name if t.rtt is not None else None))
        server = FastTransport(f"rapid_tcp_{t.name}_server", "TCPv4", None, t.interfaces, None, (ds.port,))
        add(server, FastParticipant(f"rapid_{t.name}_tcp_server",
                                    f"the discovery server of {t.name} over TCP (fastdds discovery -x)",
                                    False, None, None, "SERVER", ds.prefix, (), (server_loc,), (), (),
                                    server.id, None, *_fast_lease(t)))
    return transports, participants


FASTDDS_NAMES = _FASTDDS
OMG_NAMES = _OMG
