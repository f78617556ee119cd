"""The link's round trip (--rtt of `rapidgen cmd` and `rapidgen conform`): waits tuned for
loopback grow by what a slow link costs, so a late answer is judged as the protocol's, not
the timer's. docs/field.md measures what these allowances meet on a lunar link."""
from __future__ import annotations

import argparse
import math

# A late joiner's first durable sample: participants (1 round trip), endpoints (1-2), the
# reader's request and the writer's history (1); one lost packet on the way costs a
# heartbeat period and a round trip more (measured on the lunar link, docs/field.md).
DISCOVERY_TRIPS = 6
MAX_RTT = 600.0  # s: beyond Mars at its closest (~6 min) a command line is the wrong tool


def round_trip(text: str) -> float:
    """argparse type: seconds, 0..MAX_RTT; anything else is a usage error (exit 2)."""
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not math.isfinite(value) or not 0 <= value <= MAX_RTT:
        raise argparse.ArgumentTypeError(f"'{text}' is not a round trip in seconds (0..{MAX_RTT:g})")
    return value


def allow(seconds: float, rtt: float, trips: float = 2.0) -> float:
    """A loopback wait over a link: an answer costs one round trip, a lost packet's repair
    another (trips=2); discovery DISCOVERY_TRIPS."""
    return seconds + trips * rtt
