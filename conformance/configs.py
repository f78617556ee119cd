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


@check("CFG-03", REQUIRED, "Each config's content equals what the descriptor implies",
       "descriptor (computed CommandConfig, AgentConfig, PositionConfig, JointConfig); 5b: entries sorted by name",
       needs=("CFG-02",))
def content(s):
    bad = []
    for t in _configs(s):
        got = _latest(s, t)
        want = _expected(s, t, got)
        if _plain(got) != _plain(want):
            g, w = _plain(got), _plain(want)
            diff = next((k for k in w if k != "hdr" and g.get(k) != w.get(k)), "?")
            bad.append(f"{t}.{diff}: {visible(str(g.get(diff)))[:120]} (expected {visible(str(w.get(diff)))[:120]})")
    expect(not bad, "the descriptor's configs", "; ".join(bad))


@check("CFG-04", REQUIRED, "Config headers name the asset (assetName) and a source (srcName)",
       "rapid-protocol.md 3 and 5: samples copy their config's header", needs=("CFG-02",))
def headers(s):
    bad = []
    for t in _configs(s):
        h = _latest(s, t).hdr
        if h.assetName != s.asset or not h.srcName:
            bad.append(f"{t}: srcName={h.srcName!r} assetName={h.assetName!r}")
    expect(not bad, f"assetName {s.asset!r} and a non-empty srcName", "; ".join(bad))


@check("CFG-05", REQUIRED, "Config serials are set and stay put while the content does not change",
       "rapid-protocol.md 5 and 5b: serial set once (start time in seconds); a new one only on a change",
       needs=("CFG-02",))
def serials(s):
    bad = []
    for t in _configs(s):
        _latest(s, t)
        got = s.client.samples(t)
        serials = [r.sample.hdr.serial for r in got]
        if not serials[-1]:
            bad.append(f"{t}: serial 0")
        contents = {repr({k: v for k, v in _plain(r.sample).items() if k != "hdr"}) for r in got}
        if len(set(serials)) > 1 and len(contents) == 1:
            bad.append(f"{t}: serial changed {serials} with the same content")
    expect(not bad, "a non-zero serial, changed only with the content", "; ".join(bad))
