"""Configs: published, durable for a late joiner, equal to what the descriptor implies,
headers and serials (rapid-protocol.md 5 and 5b)."""
from __future__ import annotations

import time

from rapidgen.textsafe import visible
from rapidgen.conform.model import REQUIRED, Blocked, Unsupported, check, expect

from .dds import qos_mismatch


def _configs(s) -> dict:
    if not s.facts.configs:
        raise Unsupported("the descriptor implies no configs")
    return s.facts.configs


@check("CFG-01", REQUIRED, "Every config the descriptor implies is published",
       "rapid-protocol.md 5: an asset publishes each *Config at start-up")
def published(s):
    missing = [t for t in _configs(s) if not s.wait_endpoint("writer", t, 3.0)]
    expect(not missing, f"writers of {', '.join(_configs(s))}", f"none for {', '.join(missing)}")


@check("CFG-02", REQUIRED, "Configs are durable: a late-joining reader gets each one",
       "rapid-protocol.md 5: reliable, transient-local, keep-last-1 (RapidConfigQos)", needs=("CFG-01",))
def durable(s):
    bad = [why for t in _configs(s) for ep in s.endpoints("writer", t) if (why := qos_mismatch(ep, "RapidConfigQos"))]
    expect(not bad, "config writers Reliable, TransientLocal, KeepLast", "; ".join(bad))
    end = time.monotonic() + s.timeout
    missing = list(_configs(s))
    while missing and time.monotonic() < end:
        missing = [t for t in missing if not s.client.samples(t)]
        time.sleep(0.05)
    expect(not missing, "each config received by a reader that joined after the asset started",
           f"nothing on {', '.join(missing)}")


def _latest(s, topic: str):
    """The latest config received on topic (waiting for it when CFG-02 was not run)."""
    got = s.latest(topic, timeout=s.timeout)
    if got is None:
        raise Blocked(f"no {topic} received (CFG-02)")
    return got


def _plain(x):
    """A received sample (or member) as plain data, float32 members as received."""
    if hasattr(x, "__dataclass_fields__"):
        return {k: _plain(getattr(x, k)) for k in x.__dataclass_fields__}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    name = getattr(x, "name", None)
    return name if name is not None and not isinstance(x, (str, int, float)) else x


def _expected(s, topic: str, sample):
    """The descriptor's config as the generated class, through the wire (float32 rounding)."""
    from rapidgen.conform.expected import config_sample
    want = config_sample(s.b, topic, sample.hdr)
    return type(want).deserialize(want.serialize())


# CommandConfig lists whose order is the asset's choice (5b: soraCore sorts entries by name,
# Astrobee keeps its config file's order): compared as multisets, keyed by name. A CommandDef's
# parameters keep their order (arguments are matched by position), as do the other configs'
# lists (valueKeys[i] describes values[i]; jointDefinitions[i] index i).
UNORDERED = {"availableSubsystems": None, "availableSubsystemTypes": "commands"}


def _unordered(config: dict) -> dict:
    """A CommandConfig (plain) with its unordered lists sorted by name (each type's
    commands too); other configs unchanged."""
    if "availableSubsystems" not in config:
        return config
    out = dict(config)
    for key, inner in UNORDERED.items():
        items = [dict(x, **{inner: sorted(x[inner], key=_key)}) if inner else x for x in config.get(key, [])]
        out[key] = sorted(items, key=_key)
    return out


def _key(x) -> tuple[str, str]:
    """By name, then by the whole entry (two entries of one name compare as a multiset too)."""
    return (str(x.get("name", "")) if isinstance(x, dict) else "", repr(x))


@check("CFG-03", REQUIRED, "Each config's content equals what the descriptor implies",
       "descriptor (computed CommandConfig, AgentConfig, PositionConfig, JointConfig); 5b: entries in any order "
       "(soraCore sorts by name)", needs=("CFG-02",))
def content(s):
    bad, order = [], []
    for t in _configs(s):
        got = _latest(s, t)
        g, w = _plain(got), _plain(_expected(s, t, got))
        g.pop("hdr", None)
        w.pop("hdr", None)
        if g == w:
            continue
        gu, wu = _unordered(g), _unordered(w)
        if gu == wu:
            order.append(f"{t}: " + ", ".join(k for k in UNORDERED if g.get(k) != w.get(k))
                         + " (or their commands) in another order than the descriptor's")
            continue
        diff = next((k for k in wu if gu.get(k) != wu.get(k)), "?")
        bad.append(f"{t}.{diff}: {visible(str(gu.get(diff)))[:120]} (expected {visible(str(wu.get(diff)))[:120]})")
    expect(not bad, "the descriptor's configs (entries of the CommandConfig in any order)", "; ".join(bad))
    if order:
        return "; ".join(order) + " (either is conformant: rapid-protocol.md 5b)"


@check("CFG-04", REQUIRED, "Config headers name the asset (assetName) and a source (srcName)",
       "rapid-protocol.md 3 and 5: samples copy their config's header", needs=("CFG-02",))
def headers(s):
    bad = []
    for t in _configs(s):
        h = _latest(s, t).hdr
        if h.assetName != s.asset or not h.srcName:
            bad.append(f"{t}: srcName={h.srcName!r} assetName={h.assetName!r}")
    expect(not bad, f"assetName {s.asset!r} and a non-empty srcName", "; ".join(bad))


# Judged at the end of the run: a serial must stay put for the whole run, and an asset that
# republishes its configs with a new serial every few seconds looks right at first. A short
# run (--only CFG-, about 2 s) could end before such an asset republishes: the configs are
# watched for SERIAL_SPAN s at least.
SERIAL_SPAN = 4.0


def _watched(s, span: float) -> None:
    """Until span s have passed since the first config sample came (now, if none came)."""
    firsts = [got[0].at for t in _configs(s) if (got := s.client.samples(t))]
    if firsts:
        time.sleep(max(0.0, min(firsts) + span - time.monotonic()))


@check("CFG-05", REQUIRED, "Config serials are set and stay put while the content does not change",
       "rapid-protocol.md 5 and 5b: serial set once (start time in seconds); a new one only on a change",
       needs=("CFG-02",), late=True)
def serials(s):
    _watched(s, SERIAL_SPAN)
    bad = []
    for t in _configs(s):
        _latest(s, t)
        got = s.client.samples(t)
        if not got[-1].sample.hdr.serial:
            bad.append(f"{t}: serial 0")
        # each run of one content: the serials it was published with, and when (seconds into the run)
        runs: list[tuple[str, list[tuple[int, float]]]] = []
        for r in got:
            content = repr({k: v for k, v in _plain(r.sample).items() if k != "hdr"})
            if not runs or runs[-1][0] != content:
                runs.append((content, []))
            seen = runs[-1][1]
            if not seen or seen[-1][0] != r.sample.hdr.serial:
                seen.append((r.sample.hdr.serial, r.at - s.started))
        for _content, seen in runs:
            if len(seen) > 1:
                shown = ", ".join(f"{serial} at {at:.1f} s" for serial, at in seen[:4])
                more = f" and {len(seen) - 4} more" if len(seen) > 4 else ""
                bad.append(f"{t}: same content republished with serial {shown}{more}")
    expect(not bad, "a non-zero serial, changed only with the content", "; ".join(bad))
