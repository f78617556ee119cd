"""The faults the spy recognises, each with a stable code (docs/spy.md lists them and a
test checks that table against DIAGNOSES). Each rule reads the Watcher's state and
yields Findings; none fires on a healthy network (the seed bridges), each is triggered
by a broken participant in tests/spy."""
from __future__ import annotations

import fnmatch
import time
from dataclasses import dataclass

from rapidgen.qos.spec import default_library

DIAGNOSES = {  # code -> one-line explanation (docs/spy.md's table says the same)
    "SPY-QOS-01": "a writer and a reader of a topic share a partition but their QoS is incompatible "
                  "(requested/offered: reliability, durability or ownership): they never match",
    "SPY-QOS-02": "a config writer is not durable (transient-local): a reader that joins later never "
                  "gets the config",
    "SPY-TYPE-01": "a writer registers a RAPID type name with another layout: readers of the real type "
                   "do not match it",
    "SPY-PART-01": "a writer is outside the partition its topic's readers (the asset) are in, or a command "
                   "names an asset whose partition it was not written in",
    "SPY-SER-01": "a sample's header serial differs from its config's: readers cannot pair them",
    "SPY-TIME-01": "header timestamps look like milliseconds since 1970 (RAPID says microseconds)",
    "SPY-ACK-01": "an ack names a cmdId that no command seen on the network carried",
    "SPY-DATA-01": "a writer sends samples that do not decode as its topic's type (e.g. invalid UTF-8, a "
                   "length past the data): each is dropped alone, its other samples are read",
}
SETTLE = 1.5  # seconds a reader of ours exists before a writer it did not match is judged
MAX_JUDGED = 64  # writers and readers of a topic compared pairwise, each (endpoint floods: the first ones)
_DURABILITY_RANK = {"Volatile": 0, "TransientLocal": 1, "Transient": 2, "Persistent": 3}
_US_PER_DAY = 86_400 * 1_000_000


@dataclass(frozen=True)
class Finding:
    code: str
    partition: str
    topic: str
    message: str

    def as_dict(self) -> dict:
        return {"code": self.code, "partition": self.partition, "topic": self.topic, "message": self.message,
                "explanation": DIAGNOSES[self.code]}

    def text(self) -> str:
        where = f"[{self.partition or '(default partition)'}] {self.topic}" if self.topic else self.partition
        return f"{self.code} {where}: {self.message}"


def diagnose(w, roles: dict, declared_pairs: dict | None = None) -> list[Finding]:
    """Every finding on what the Watcher saw. roles: (partition, topic) -> role."""
    out: list[Finding] = []
    for rule in (_qos, _durable_configs, _types, _partitions, _serials, _timestamps, _acks, _undecodable):
        out += rule(w, roles, declared_pairs or {})
    seen, unique = set(), []
    for f in out:
        if (f.code, f.partition, f.topic, f.message) not in seen:
            seen.add((f.code, f.partition, f.topic, f.message))
            unique.append(f)
    return sorted(unique, key=lambda f: (f.partition, f.topic, f.code))


def _share(a: tuple[str, ...], b: tuple[str, ...]) -> str | None:
    """A partition both endpoints are in (either side may use wildcards), else None."""
    common = set(a) & set(b)
    if common:
        return min(common)
    if not any("*" in x or "?" in x for x in (*a, *b)):
        return None
    for x in a:
        for y in b:
            if x == y or fnmatch.fnmatchcase(x, y) or fnmatch.fnmatchcase(y, x):
                return x if "*" not in x else y
    return None


def _name(w, participant: str) -> str:
    p = w.discovery.participants.get(participant)
    props = p.properties if p else {}
    proc = props.get("__ProcessName")
    return f"{proc}[{props.get('__Pid')}]" if proc else participant[:8]


def _by_topic(w) -> dict[str, dict[str, list]]:
    """topic -> {"writer": [...], "reader": [...]}: endpoints but those only in partitions a
    cap left unread, at most MAX_JUDGED of each kind per topic."""
    out: dict[str, dict[str, list]] = {}
    for e in w.discovery.endpoints.values():
        if all(p in w.unread_partitions for p in e.partitions):
            continue
        kinds = out.setdefault(e.topic, {"writer": [], "reader": []})
        if len(kinds[e.kind]) < MAX_JUDGED:
            kinds[e.kind].append(e)
    return out


def _pairs_of(w):
    """(writer, reader) of each topic, from _by_topic."""
    for eps in _by_topic(w).values():
        for wr in eps["writer"]:
            for rd in eps["reader"]:
                yield wr, rd


def _qos(w, roles, _pairs):
    lib = default_library()
    for wr, rd in _pairs_of(w):
        part = _share(wr.partitions, rd.partitions)
        if part is None or wr.participant == rd.participant:
            continue
        expected = lib.profile_for_type(wr.type_name.replace(".", "::"))
        wq, rq = lib.effective(expected) if expected else (None, None)
        problems = []
        if rd.qos.reliability == "Reliable" and wr.qos.reliability == "BestEffort":
            side = _side(wq is not None and wq.reliability == "reliable",
                         rq is not None and rq.reliability != "reliable")
            problems.append(f"reliability: reader requests RELIABLE, writer offers BEST_EFFORT ({side})")
        wd, rdur = _DURABILITY_RANK.get(wr.qos.durability or "", 0), _DURABILITY_RANK.get(rd.qos.durability or "", 0)
        if rdur > wd:
            side = _side(wq is not None and wq.durability != "volatile",
                         rq is not None and rq.durability == "volatile")
            problems.append(f"durability: reader requests {rd.qos.durability}, writer offers "
                            f"{wr.qos.durability} ({side})")
        if wr.qos.ownership and rd.qos.ownership and wr.qos.ownership != rd.qos.ownership:
            problems.append(f"ownership: reader {rd.qos.ownership}, writer {wr.qos.ownership}")
        for p in problems:
            yield Finding("SPY-QOS-01", part, wr.topic, f"writer {_name(w, wr.participant)} and reader "
                          f"{_name(w, rd.participant)}: {p}" + (f"; profile {expected}" if expected else ""))


def _side(writer_should: bool | None, reader_off: bool | None) -> str:
    """Which side leaves the topic's profile: writer_should = the profile wants the
    writer to offer what the reader asks; reader_off = the profile would not ask it."""
    if writer_should and not reader_off:
        return "the writer is off its profile"
    if reader_off and not writer_should:
        return "the reader is off its profile"
    return "both sides differ from the profile" if writer_should and reader_off else "no profile decides"


def _durable_configs(w, roles, _pairs):
    for e in w.discovery.endpoints.values():
        if e.kind != "writer" or e.qos.durability not in ("Volatile", None):
            continue
        for part in e.partitions:
            if roles.get((part, e.topic)) == "config" or e.type_name.endswith("Config"):
                yield Finding("SPY-QOS-02", part, e.topic, f"writer {_name(w, e.participant)} offers "
                              f"{e.qos.durability or 'no durability'} (RapidConfigQos: TransientLocal)")


def _types(w, roles, _pairs):
    now = time.monotonic()
    topics = _by_topic(w)
    for (topic, part, reliable, durable), st in list(w.streams.items()):
        if now - st.created < SETTLE:
            continue
        matched = st.matched()
        for e in topics.get(topic, {}).get("writer", []):
            if part not in e.partitions or e.key in matched or not e.type_name.startswith("rapid::"):
                continue
            if (e.qos.reliability == "Reliable") != reliable or ((e.qos.durability or "") in
                                                                 ("TransientLocal", "Transient", "Persistent")) != durable:
                continue
            yield Finding("SPY-TYPE-01", part, topic, f"writer {_name(w, e.participant)} registers {e.type_name} "
                          f"but does not match a reader of RAPID's {e.type_name}: {layout_diff(w, e, st)}")


def layout_diff(w, endpoint, stream) -> str:
    """Which member differs, from the writer's announced type information (XTypes type
    lookup); 'type information unavailable' when the writer sent none."""
    from rapidgen.spy.layout import first_difference
    tid = w.type_ids.get(endpoint.key)
    ours = w.type_class(endpoint.type_name)
    if tid is None or ours is None:
        return "layout differs (the writer sent no type information)"
    try:
        from cyclonedds.dynamic import get_types_for_typeid
        theirs, _ = get_types_for_typeid(w.dp, tid, 1_000_000_000)  # timeout in ns
    except Exception as exc:  # type lookup failed or timed out
        return f"layout differs (type information not resolved: {type(exc).__name__})"
    return first_difference(ours, theirs) or "layout differs in bounds or extensibility"


def _partitions(w, roles, _pairs):
    for eps in _by_topic(w).values():
        for wr in eps["writer"]:
            readers = [e for e in eps["reader"] if e.participant != wr.participant]
            if readers and not any(_share(wr.partitions, r.partitions) for r in readers):
                where = sorted({p for r in readers for p in r.partitions})
                yield Finding("SPY-PART-01", wr.partitions[0], wr.topic,
                              f"writer {_name(w, wr.participant)} is in partition(s) "
                              f"{', '.join(map(repr, wr.partitions))}; "
                              f"the readers of {wr.topic} are in {', '.join(map(repr, where))}")
    partition_of = _asset_partitions(w)
    for st in w.streams.values():
        if roles.get((st.partition, st.topic)) != "command" and not st.type_name.endswith("::Command"):
            continue
        for s in st.seen:
            home = partition_of.get(s.asset)
            if home is not None and home != st.partition:
                yield Finding("SPY-PART-01", st.partition, st.topic, f"commands for {s.asset} (cmdId "
                              f"{s.cmd_id!r}) are written in partition {st.partition!r}; {s.asset} reads "
                              f"commands in {home!r}")
                break


def _asset_partitions(w) -> dict[str, str]:
    """asset name -> the partition its configs are published in."""
    out: dict[str, str] = {}
    for st in w.streams.values():
        if st.type_name.endswith("Config"):
            if st.latest is not None and st.latest.asset:
                out.setdefault(st.latest.asset, st.partition)
    return out


def _serials(w, roles, pairs):
    from rapidgen.spy.model import pair_config
    by_part: dict[str, set[str]] = {}
    for st in w.streams.values():
        if roles.get((st.partition, st.topic)) == "config" or st.type_name.endswith("Config"):
            by_part.setdefault(st.partition, set()).add(st.topic)
    for st in w.streams.values():
        cfg_topic = pair_config(st.topic, by_part.get(st.partition, set()), pairs.get(st.partition))
        if cfg_topic is None or cfg_topic == st.topic or not st.by_writer:
            continue
        configs = w.seen(cfg_topic, st.partition)
        if not configs:
            continue
        owner = {c.writer and _participant(w, c.writer): c.serial for c in configs}  # latest wins
        bad = []
        seen = st.seen
        for s in seen:
            who = s.writer and _participant(w, s.writer)
            serial = owner.get(who, configs[-1].serial)
            if s.serial != serial:
                bad.append((s, who, serial))
        if bad:
            s, who, serial = bad[-1]
            source = "the same participant" if who in owner else \
                _name(w, (configs[-1].writer and _participant(w, configs[-1].writer)) or "?")
            yield Finding("SPY-SER-01", st.partition, st.topic, f"{len(bad)} of {len(seen)} samples carry serial "
                          f"{s.serial} (e.g. from {_name(w, who or '?')}); {cfg_topic} from {source} has serial "
                          f"{serial}")


def _participant(w, writer: str) -> str | None:
    e = w.discovery.endpoints.get(writer)
    return e.participant if e is not None else None


def _timestamps(w, roles, _pairs):
    now_us = time.time() * 1e6
    for st in w.streams.values():
        for s in reversed(st.seen[-20:]):
            ts = s.time_stamp
            if ts is not None and ts > 0 and abs(ts * 1000 - now_us) < 30 * _US_PER_DAY \
                    and abs(ts * 1000 - now_us) < abs(ts - now_us):
                yield Finding("SPY-TIME-01", st.partition, st.topic,
                              f"hdr.timeStamp {ts} is {time.strftime('%Y-%m-%d', time.gmtime(ts / 1000))} read as "
                              "milliseconds, 1970 read as microseconds")
                break


def _acks(w, roles, _pairs):
    sent = w.cmd_ids
    listening = {st.partition: st.created for st in w.streams.values() if st.type_name.endswith("::Command")}
    for st in w.streams.values():
        if not st.type_name.endswith("::Ack"):
            continue
        since = max(w.started, listening.get(st.partition, w.started))
        ghosts = [s for s in st.seen if s.at >= since + 1.0
                  and (s.stamp is None or s.stamp >= w.started_wall + 1.0)  # earlier: commands we could not see
                  and s.cmd_id is not None and s.cmd_id not in sent]
        if ghosts:
            ids = sorted({a.cmd_id or "" for a in ghosts})
            yield Finding("SPY-ACK-01", st.partition, st.topic, f"{len(ghosts)} ack(s) name {len(ids)} cmdId(s) no "
                          f"command seen carried (e.g. {ids[0]!r} from {ghosts[0].src or '?'!r})")


def _undecodable(w, roles, _pairs):
    for d in w.dropped():
        who = f"writer {d['writer']} ({_name(w, d['participant'])})" if d["participant"] else d["writer"]
        yield Finding("SPY-DATA-01", d["partition"], d["topic"], f"{d['count']} sample(s) from {who} "
                      f"did not decode and were dropped ({d['error']})")
