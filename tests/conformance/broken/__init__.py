"""Deliberately broken assets for the conformance tests: a seed asset's simulated bridge
with one protocol rule broken by patching the runtime in the child process only.

    python -m tests.conformance.broken KIND GENERATED_PYTHON_DIR PACKAGE DOMAIN

Prints "bridge ready" like the real bridge. KINDS maps each kind to the check it aims at
(None: a variant the suite must accept, e.g. Astrobee's ack habits). A kind is a function
of the Asset being broken (asset.py), registered by area in the modules imported below;
it runs once the bridge is built and before it starts (nothing is written yet)."""
from __future__ import annotations

from typing import Callable

KINDS: dict[str, str | None] = {}
PATCHES: dict[str, Callable] = {}


def kind(name: str, aims: str | None):
    """Register fn(asset) as the broken asset `name`, failing check `aims` and no other (the
    checks it keeps from judging are BLOCKED); None: a variant that must pass every check."""
    def register(fn: Callable) -> Callable:
        if name in KINDS:
            raise ValueError(f"broken kind {name} registered twice")
        KINDS[name], PATCHES[name] = aims, fn
        return fn
    return register


from . import access, commands, configs, dds, queue, spec, telemetry  # noqa: E402,F401  (registers the kinds)
