"""argparse value types shared by the subcommands that join a DDS domain."""
from __future__ import annotations

import argparse

MAX_DOMAIN_ID = 232  # the RTPS port mapping's limit with the default port parameters


def domain_id(text: str) -> int:
    """A DDS domain id, 0..232: anything else is a usage error (exit 2), not a middleware failure."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a domain id (0..{MAX_DOMAIN_ID})") from None
    if not 0 <= value <= MAX_DOMAIN_ID:
        raise argparse.ArgumentTypeError(f"domain {value} is outside 0..{MAX_DOMAIN_ID}")
    return value
