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


def _seconds(text: str, zero_ok: bool, must: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number of seconds") from None
    if not (value >= 0 if zero_ok else value > 0) or value == float("inf"):
        raise argparse.ArgumentTypeError(f"'{text}' must be {must}")
    return value


def positive_seconds(text: str) -> float:
    """A duration (--seconds, --split-seconds): finite and above 0."""
    return _seconds(text, False, "a positive number of seconds")


def seconds_from_start(text: str) -> float:
    """An offset into a recording (--from, --to): finite, 0 or more."""
    return _seconds(text, True, "0 or more seconds from the recording's start")


def positive_factor(text: str) -> float:
    """A speed factor (--rate): finite and above 0."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number") from None
    if not value > 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"'{text}' must be a positive number")
    return value
