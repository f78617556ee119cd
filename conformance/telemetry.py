"""Telemetry: samples and states pair with their config (serial, alignment), carry
microsecond timestamps and arrive at the declared rates (rapid-protocol.md 3, 5, 5b)."""
from __future__ import annotations

import time

from rapidgen.conform.model import RECOMMENDED, REQUIRED, Blocked, Unsupported, check, expect

RATE_TOLERANCE = 0.25  # measured over loopback in a Python reader; 5b: telemetry may be dropped
MIN_WINDOW = 3.0  # s of samples before a rate is judged
MATCH_WAIT = 10.0  # s for the asset's telemetry writers to match ours before their samples are awaited
MICROS_2001 = 978_307_200 * 1_000_000  # a microsecond stamp after 2001; milliseconds are 1000x smaller


def _topics(s, paired: bool = True) -> list[dict]:
    pubs = s.facts.sample_topics(paired)
    if not pubs:
        raise Unsupported("the descriptor declares no " + ("agent, position or joint telemetry" if paired
                                                           else "other telemetry") + " with a rate")
    return pubs


def _wait_all(s, pubs, timeout: float) -> dict:
    end = time.monotonic() + timeout
    while True:
        got = {p["topic"]: s.client.samples(p["topic"]) for p in pubs}
        if all(got.values()) or time.monotonic() > end:
            return got
        time.sleep(0.05)


@check("TEL-01", REQUIRED, "Every declared agent, position and joint telemetry topic publishes",
       "descriptor: telemetry entries and rates")
def publishes(s):
    _published(s, _topics(s))


@check("TEL-08", RECOMMENDED, "Other declared telemetry with a rate (images, extension types) publishes",
       "descriptor: telemetry entries and rates", late=True)
def others(s):
    _published(s, _topics(s, paired=False))


def _matched(s, pubs, timeout: float) -> None:
    """Until our reader of each topic is matched with an asset's writer, or timeout."""
    end = time.monotonic() + timeout
    while time.monotonic() < end and not all(
            any(s.client.matched_asset(r, True) for r in s.client.listened.get(p["topic"], ())) for p in pubs):
        time.sleep(0.05)


def _published(s, pubs):
    # The window runs from the matches: discovery of a writer is DDS-06's to judge, and on a
    # loaded machine (or over a link) it can take longer than a window of a few periods.
    _matched(s, pubs, s.allow(MATCH_WAIT))
    got = _wait_all(s, pubs, s.allow(max(3.0, 2.5 / min(p["rate"] for p in pubs))))
    missing = [t for t, v in got.items() if not v]
    expect(not missing, "samples on every declared telemetry topic", f"none on {', '.join(missing)}")


def _paired(s):
    """(publication, its config's topic, the latest config, the samples) per paired topic. Each
    config is awaited (CFG-02 may not have run, and on a loaded machine it can come after
    TEL-01's samples): a topic skipped for want of its config would pass its check unjudged."""
    for p in _topics(s):
        cfg = s.facts.config_of(p["topic"])
        if not cfg:
            continue
        latest = s.latest(cfg, timeout=s.timeout)
        if latest is None:
            raise Blocked(f"no {cfg} received (CFG-02)")
        got = s.client.wait_sample(p["topic"], s.allow(MATCH_WAIT))
        if got:  # (none at all is TEL-01's finding)
            yield p, cfg, latest, got


# A sample and its config travel on two topics: around a config republished with a new
# serial, a sample may come a little before or after it with either serial.
RACE = 1.0


# Judged at the end of the run, on every sample kept (as CFG-05): the rule holds for the whole run.
@check("TEL-02", REQUIRED, "Sample serials equal their config's serial",
       "rapid-protocol.md 5: samples copy the config's header, serial included", needs=("TEL-01", "CFG-02"), late=True)
def serial(s):
    bad = []
    for p, cfg_topic, cfg, got in _paired(s):
        configs = [(r.at, r.sample.hdr.serial) for r in s.client.samples(cfg_topic)]
        wrong = [r for r in got if r.sample.hdr.serial not in _serials_at(configs, r.at)]
        if wrong:
            bad.append(f"{p['topic']}: {sorted({r.sample.hdr.serial for r in wrong})[:3]} (config {cfg.hdr.serial})")
    expect(not bad, "every sample's serial equal to its config's", "; ".join(bad))


def _serials_at(configs: list[tuple[float, int]], at: float) -> set[int]:
    """The serials a sample that arrived at `at` may carry: its config's then (the latest
    received before it, else the first), and any config's received within RACE of it."""
    before = [serial for t, serial in configs if t <= at]
    out = {before[-1] if before else configs[0][1]} if configs else set()
    return out | {serial for t, serial in configs if abs(t - at) <= RACE}


def _disc(u) -> str:
    return getattr(u.discriminator, "name", str(u.discriminator))


@check("TEL-03", REQUIRED, "Values align with the config (valueKeys, jointDefinitions) by position and type",
       "rapid-protocol.md 5: valueKeys[i] describes values[i]; jointDefinitions[i] index i of each sequence",
       needs=("TEL-01", "CFG-02"))
def aligned(s):
    bad = []
    for p, _cfg_topic, cfg, got in _paired(s):
        smp = got[-1].sample
        if hasattr(cfg, "valueKeys") and hasattr(smp, "values"):
            want = [_disc(k.value) for k in cfg.valueKeys]
            seen = [_disc(v) for v in smp.values]
            if want != seen:
                bad.append(f"{p['topic']}: values {seen} for valueKeys {want}")
        if hasattr(cfg, "jointDefinitions"):
            n = len(cfg.jointDefinitions)
            for name in ("anglePos", "angleVel", "angleAcc", "current", "torque", "temperature", "status"):
                seq = getattr(smp, name, [])
                if seq and len(seq) != n or name == "anglePos" and len(seq) != n:
                    bad.append(f"{p['topic']}.{name}: {len(seq)} entries for {n} jointDefinitions")
    expect(not bad, "one value per key, of the key's DataType", "; ".join(bad))


ADVANCE_OVER = 1.0  # s of arrivals over which a topic's stamps must be seen to advance
ADVANCE = (0.5, 2.0)  # stamps advance between these times the arrival time over that span


# Judged at the end of the run (samples of the whole run): stamps must be microseconds, recent,
# and advance with time (a frozen stamp passed when only the last sample's age was looked at).
@check("TEL-04", REQUIRED, "Sample timestamps are microseconds since 1970, recent, and advance with time",
       "rapid-protocol.md 3 and 5b: timeStamp in microseconds, the data's time (milliseconds are a known sender bug)",
       needs=("TEL-01",), late=True)
def stamps(s):
    pubs = _topics(s)
    _wait_span(s, pubs, s.allow(max(3.0, 2.5 / min(p["rate"] for p in pubs))))
    bad = []
    now = time.time_ns() // 1000
    for p in pubs:
        got = s.client.samples(p["topic"])
        if not got:
            continue
        ts = got[-1].sample.hdr.timeStamp
        if ts < MICROS_2001:
            bad.append(f"{p['topic']}: {ts} (milliseconds?)" if ts > MICROS_2001 // 1000 else f"{p['topic']}: {ts}")
            continue
        if abs(now - ts) > 60_000_000:
            bad.append(f"{p['topic']}: {(now - ts) / 1e6:.1f} s from now")
            continue
        first, last = got[0], got[-1]
        span = last.at - first.at
        if span < ADVANCE_OVER:
            continue  # too few samples to say (TEL-06 judges the rates)
        moved = (last.sample.hdr.timeStamp - first.sample.hdr.timeStamp) / 1e6
        if not ADVANCE[0] * span <= moved <= ADVANCE[1] * span:
            distinct = len({r.sample.hdr.timeStamp for r in got})
            bad.append(f"{p['topic']}: stamps advanced {moved:.2f} s over {span:.1f} s of arrivals "
                       f"({len(got)} samples, {distinct} distinct stamp(s); first {first.sample.hdr.timeStamp})")
    expect(not bad, "microseconds since the epoch, within 60 s of now, advancing with time", "; ".join(bad))


def _wait_span(s, pubs, timeout: float) -> None:
    """Until each topic's samples span ADVANCE_OVER s of arrivals (or the timeout)."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        spans = [s.client.samples(p["topic"]) for p in pubs]
        if all(g and g[-1].at - g[0].at >= ADVANCE_OVER for g in spans):
            return
        time.sleep(0.05)


@check("TEL-05", REQUIRED, "Sample headers name the asset (assetName) and a source (srcName)",
       "rapid-protocol.md 3 and 5", needs=("TEL-01",))
def headers(s):
    bad = []
    for p in _topics(s):
        for r in s.client.samples(p["topic"])[-1:]:
            h = r.sample.hdr
            if h.assetName != s.asset or not h.srcName:
                bad.append(f"{p['topic']}: srcName={h.srcName!r} assetName={h.assetName!r}")
    expect(not bad, f"assetName {s.asset!r}, non-empty srcName", "; ".join(bad))


@check("TEL-06", REQUIRED, f"Declared rates are met within {RATE_TOLERANCE:.0%}", "descriptor: telemetry rate [Hz]",
       needs=("TEL-01", "TEL-04"), late=True)
def rates(s):
    pubs = _topics(s)
    window = max(MIN_WINDOW, 4.0 / min(p["rate"] for p in pubs))
    first = min(r.at for p in pubs for r in s.client.samples(p["topic"])[:1])
    left = first + window - time.monotonic()
    if left > 0:
        time.sleep(left)
    bad, seen = [], []
    for p in pubs:
        got = s.client.samples(p["topic"])
        if len(got) < 2:
            bad.append(f"{p['topic']}: {len(got)} samples")
            continue
        # the sender's stamps (microseconds; arrival times bunch per poll at high rates), median
        # gap: one late, lost or bunched sample does not move it
        stamps = [r.sample.hdr.timeStamp for r in got]
        gaps = sorted((b - a) / 1e6 for a, b in zip(stamps, stamps[1:]))
        median = gaps[len(gaps) // 2]
        hz = 1.0 / median if median > 0 else float("inf")
        seen.append(f"{p['topic']} {hz:.3g}/{p['rate']:g} Hz")
        if abs(hz - p["rate"]) > RATE_TOLERANCE * p["rate"]:
            bad.append(f"{p['topic']}: {hz:.3g} Hz (declared {p['rate']:g})")
    expect(not bad, "each declared rate", "; ".join(bad))
    return ", ".join(seen)


@check("TEL-07", RECOMMENDED, "Values lie inside their declared ranges", "descriptor: telemetry value range",
       needs=("TEL-03",))
def ranges(s):
    bad = []
    for p in _topics(s):
        entry, got = s.facts.entry_of(p["topic"]), s.client.samples(p["topic"])
        if not entry or not got or not hasattr(got[-1].sample, "values"):
            continue
        for decl, v in zip(entry.get("values", []), got[-1].sample.values):
            x = v.value
            if isinstance(x, (int, float)) and not isinstance(x, bool):
                lo, hi = decl.get("min"), decl.get("max")
                if (lo is not None and x < lo - 1e-6) or (hi is not None and x > hi + 1e-6):
                    bad.append(f"{p['topic']} {decl['name']}={x:g} not in [{lo}, {hi}]")
    expect(not bad, "values within their ranges", "; ".join(bad))
