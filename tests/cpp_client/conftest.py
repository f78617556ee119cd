"""The C++ ground-side client and K10's test bridge, built once per session in the seeds'
build (tests/cpp_runtime/build.py client_programs), -Wall -Wextra -Werror.
RAPIDGEN_CPP_CLIENT_BUILD=DIR uses the programs already built in DIR (a seeds build with
K10: cmake -S tests/cpp_runtime/seeds ..., see bench/cpp_bridge.py) instead."""
from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.cpp_runtime import build as B


@pytest.fixture(scope="session")
def programs(tmp_path_factory) -> dict[str, Path]:
    """"k10": K10's generated bridge, "cmd": rapid_cmd on K10's package, "bridge_test":
    K10's bridge taking --break KIND, its command intake under ASan/UBSan."""
    built = os.environ.get("RAPIDGEN_CPP_CLIENT_BUILD")
    if built:
        d = Path(built)
        return {"k10": d / "k10" / "rapid_k10red_bridge", "cmd": d / "rapid_k10red_cmd",
                "bridge_test": d / "rapid_k10red_bridge_test"}
    return {"k10": B.seed_bridges(tmp_path_factory)["k10"], **B.client_programs(tmp_path_factory)}
