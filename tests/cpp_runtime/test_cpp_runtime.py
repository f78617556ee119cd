"""The C++ asset runtime (runtime/cpp): built with -Wall -Wextra -Werror (conftest.py, once
per session), its GoogleTest suite of the protocol logic run without DDS."""
from __future__ import annotations

import re
import subprocess


def test_logic_suite_passes(runtime_build):
    res = subprocess.run([str(runtime_build / "logic"), "--gtest_brief=1"], capture_output=True, text=True,
                         timeout=300)
    assert res.returncode == 0, res.stdout[-6000:] + res.stderr[-3000:]
    ran = re.search(r"\[==========\] (\d+) tests", res.stdout)
    assert ran and int(ran.group(1)) >= 30, res.stdout[-2000:]
