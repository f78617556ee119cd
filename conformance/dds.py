"""DDS: what the asset's endpoints announce in discovery (rapid-protocol.md 1, 5b, 6)."""
from __future__ import annotations

from collections.abc import Set as AbstractSet

from rapidgen.textsafe import visible
from rapidgen.conform.model import REQUIRED, check, expect

PROFILES = {  # profile -> (reliability, durability, history kind): rapid-protocol.md 6
    "RapidBestEffortQos": ("BestEffort", "Volatile", "KeepLast"),
    "RapidSampleQos": ("BestEffort", "Volatile", "KeepLast"),
    "RapidReliableQos": ("Reliable", "Volatile", "KeepAll"),
    "RapidReliableDurableQos": ("Reliable", "TransientLocal", "KeepLast"),
    "RapidConfigQos": ("Reliable", "TransientLocal", "KeepLast"),
    "RapidStateQos": ("Reliable", "TransientLocal", "KeepLast"),
}
ALSO = {"rapid::JointSample": {"RapidReliableDurableQos"}}  # 5b: some deployments
# XTypes' TYPE_CONSISTENCY_ENFORCEMENT policy id: Cyclone reports a writer whose type is not
# assignable to the reader's as incompatible QoS of this policy. That is DDS-07's finding,
# not DDS-03's (DDS-07 needs DDS-03, so counting it here would leave DDS-07 never judged).
TYPE_CONSISTENCY = 24


def qos_mismatch(ep, profile: str, accept: AbstractSet[str] = frozenset()) -> str | None:
    """Why the endpoint's announced QoS is none of the profiles, or None. History is
    compared by kind only (depth is the endpoint's own business and is not matched)."""
    for name in (profile, *accept):
        want = PROFILES.get(name.split("::")[-1])
        if want is None:
            return None
        got = (ep.qos.reliability, ep.qos.durability, _history(ep.qos) or want[2])
        if got == want:
            return None
    want = PROFILES[profile.split("::")[-1]]
    return f"{ep.topic}: {ep.qos.text()} (profile {profile.split('::')[-1]}: {', '.join(want)})"


def _history(qos) -> str | None:
    """The announced history kind, or None when it may not have been announced: DDSI's
    discovery data need not carry history (Fast DDS 2.9 leaves it out) and Cyclone shows
    a missing policy as its default KeepLast(1), so that value proves nothing."""
    if qos.history == "KeepLast" and qos.depth in (1, None):
        return None
    return qos.history


def profile_of(s, topic: str) -> str:
    return s.b.qos.key(topic).split("::")[-1]


@check("DDS-01", REQUIRED, "State and sample writers offer their topic's QoS profile", "rapid-protocol.md 6")
def writer_qos(s):
    own = {"rapid_ack"} | set(s.facts.configs)  # CMD-13 and CFG-02 judge these
    bad = []
    for p in s.facts.publications:
        if p["topic"] in own:
            continue
        for ep in s.endpoints("writer", p["topic"]):
            why = qos_mismatch(ep, p["qos"], ALSO.get(p["type"], set()))
            if why:
                bad.append(why)
    expect(not bad, "each writer's reliability, durability and history as its profile", "; ".join(bad))


@check("DDS-02", REQUIRED, "The command reader requests the Command profile (reliable, volatile, keep all)",
       "rapid-protocol.md 6: Command -> RapidReliableQos; 5: commands cannot be dropped")
def reader_qos(s):
    s.needs_commands()
    eps = s.wait_endpoint("reader", "rapid_command")
    expect(bool(eps), "a reader of rapid_command", "none")
    bad = [b for ep in eps if (b := qos_mismatch(ep, "RapidReliableQos"))]
    expect(not bad, "Reliable, Volatile, KeepAll", "; ".join(bad))


@check("DDS-04", REQUIRED, "Registered type names are the RAPID scoped names (rapid::X)",
       "rapid-protocol.md 1: DDS type names carry the module path with ::")
def type_names(s):
    want = {p["topic"]: p["type"] for p in s.facts.publications}
    want["rapid_command"] = "rapid::Command"
    bad = [f"{e.topic}: {visible(e.type_name)}" for e in s.endpoints()
           if e.topic in want and e.type_name != want[e.topic]]
    expect(not bad, "the descriptor's types (" + ", ".join(sorted(set(want.values()))[:4]) + ", ...)", "; ".join(bad))


@check("DDS-05", REQUIRED, "Every endpoint is in the partition named after the asset",
       "rapid-protocol.md 6: assets set the DDS PARTITION to their own name")
def partition(s):
    names = {p["topic"] for p in s.facts.publications} | {"rapid_command"}
    bad = [f"{e.kind} {e.topic}: {visible(str(list(e.qos.partitions)))}" for e in s.endpoints()
           if e.topic in names and s.facts.partition not in e.qos.partitions]
    expect(not bad, f"partition {s.facts.partition!r}", "; ".join(bad))


# A missing queue or access-control state writer is judged here once (QUE-01 and ACC-01
# are then BLOCKED). A missing telemetry writer fails TEL-01 too: its samples never come.
@check("DDS-06", REQUIRED, "Every declared state topic and paired telemetry topic has a writer",
       "descriptor: publications (queue and access-control state; agent, position, joint telemetry)")
def declared_writers(s):
    topics = [p["topic"] for p in s.facts.publications if p["role"] == "state" and s.facts.entry_of(p["topic"]) is None]
    topics += [p["topic"] for p in s.facts.sample_topics()]
    missing = [t for t in topics if not s.wait_endpoint("writer", t, 3.0)]  # discovery on a loaded machine
    expect(not missing, "a writer per declared topic", f"no writer of {', '.join(missing)}")


@check("DDS-03", REQUIRED, "No incompatible QoS between the asset and profile endpoints",
       "rapid-protocol.md 6 (requested/offered incompatible QoS status)", needs=("DDS-01", "DDS-02", "CFG-02", "CMD-13"),
       late=True)
def incompatible(s):
    bad: list[str] = []
    strangers: list[str] = []
    for t, found in sorted(s.client.incompatible.items()):
        why = sorted({f"{side} incompatible QoS (policy id {pid})" for side, pid in found if pid != TYPE_CONSISTENCY})
        if not why:
            continue
        # The status does not say whose endpoint it was: it is the asset's when one of the
        # asset's endpoints on the topic (in its partition) is not matched with ours.
        kind = "reader" if t == "rapid_command" else "writer"
        ours = s.client.matched_keys(t)
        unmatched = [e for e in s.endpoints(kind, t) if s.facts.partition in e.partitions and e.key not in ours]
        (bad if unmatched else strangers).append(f"{t}: {', '.join(why)}")
    expect(not bad, "no incompatible-QoS status on the runner's profile endpoints", "; ".join(bad))
    if strangers:
        return "not the asset's (each of its endpoints on the topic is matched): " + "; ".join(strangers)


@check("DDS-07", REQUIRED, "Writers with a RAPID type name are matched (their type is RAPID's)",
       "rapid-protocol.md 1 and dds-local: a right name with another layout matches nothing", needs=("DDS-03",),
       late=True)
def types_match(s):
    bad = []
    want = s.topics()
    for topic, reader in s.client.readers.items():
        # a writer with another type name is DDS-04's (Cyclone may match it or not)
        eps = [ep for ep in s.endpoints("writer", topic) if ep.type_name == want.get(topic)]
        if not eps:
            continue
        matched = {str(k) for k in _matched_keys(reader)}
        for ep in eps:
            if s.facts.partition in ep.qos.partitions and ep.key not in matched:
                bad.append(f"{topic} ({ep.type_name})")
    expect(not bad, "every writer matched by a reader of the RAPID type", f"unmatched: {', '.join(bad)}")


def _matched_keys(reader):
    out = []
    for h in reader.get_matched_publications():
        try:
            out.append(reader.get_matched_publication_data(h).key)
        except Exception:  # a writer that left meanwhile
            pass
    return out
