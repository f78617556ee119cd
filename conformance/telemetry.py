"""Telemetry: samples and states pair with their config (serial, alignment), carry
microsecond timestamps and arrive at the declared rates (rapid-protocol.md 3, 5, 5b)."""
from __future__ import annotations

import time

from rapidgen.conform.model import RECOMMENDED, REQUIRED, Unsupported, check, expect

RATE_TOLERANCE = 0.25  # measured over loopback in a Python reader; 5b: telemetry may be dropped
MIN_WINDOW = 3.0  # s of samples before a rate is judged
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


def _published(s, pubs):
    got = _wait_all(s, pubs, max(3.0, 2.5 / min(p["rate"] for p in pubs)))
    missing = [t for t, v in got.items() if not v]
    expect(not missing, "samples on every declared telemetry topic", f"none on {', '.join(missing)}")


def _paired(s):
    for p in _topics(s):
        cfg = s.facts.config_of(p["topic"])
        got = s.client.samples(p["topic"])
        if cfg and got and s.latest(cfg) is not None:
            yield p, cfg, s.latest(cfg), got


@check("TEL-02", REQUIRED, "Sample serials equal their config's serial",
       "rapid-protocol.md 5: samples copy the config's header, serial included", needs=("TEL-01", "CFG-02"))
def serial(s):
    bad = [f"{p['topic']}: {sorted({r.sample.hdr.serial for r in got})[:3]} (config {cfg.hdr.serial})"
           for p, _c, cfg, got in _paired(s) if any(r.sample.hdr.serial != cfg.hdr.serial for r in got)]
    expect(not bad, "every sample's serial equal to its config's", "; ".join(bad))


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


@check("TEL-04", REQUIRED, "Sample timestamps are microseconds since 1970 and recent",
       "rapid-protocol.md 3 and 5b: timeStamp in microseconds (milliseconds are a known sender bug)",
       needs=("TEL-01",))
def stamps(s):
    bad = []
    now = time.time_ns() // 1000
    for p in _topics(s):
        got = s.client.samples(p["topic"])
        if not got:
            continue
        ts = got[-1].sample.hdr.timeStamp
        if ts < MICROS_2001:
            bad.append(f"{p['topic']}: {ts} (milliseconds?)" if ts > MICROS_2001 // 1000 else f"{p['topic']}: {ts}")
        elif abs(now - ts) > 60_000_000:
            bad.append(f"{p['topic']}: {(now - ts) / 1e6:.1f} s from now")
    expect(not bad, "microseconds since the epoch, within 60 s of now", "; ".join(bad))


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
