"""`rapidgen conform` refused by DDS Security leaves no DDS behind when it returns, and ends
with its own exit code (runtime/rapid_runtime/teardown.py).

Before, the refused run's participant sat in reference cycles, and cyclonedds-python's
__del__ deletes nothing for an entity the cyclic collector frees: the participant's threads
ran until the process ended, and beside a secured bridge, under load, about 2 runs in 100
ended with SIGSEGV (-11) after the refusal (Cyclone's receive thread calling OpenSSL after
its exit handler). The crash needs that race; what makes it possible does not: Cyclone's
threads still running once the command has returned. tests/secure/refused_exit.py runs the command in its
own process (a private network namespace, the suite's DOMAIN) and says which threads are left.
The other live tools: test_tools_teardown.py; the secured bridge beside a refused run:
test_python_tools_secured.py."""
from __future__ import annotations

import pytest

from tests.secure.conftest import exited
from tests.secure.test_tools_teardown import run_tool


# Conformance: audit only (its command writer is refused); Outsider: watch only (its topic is)
@pytest.mark.parametrize("enclave", ["Conformance", "Outsider"])
def test_a_refused_conform_returns_with_no_dds_thread_left_and_exits_1(keystores, enclave):
    res, left = run_tool("conform", keystores, enclave)
    exited(res.returncode, 1, res)
    assert "DDS Security refused what the runner needs" in res.stderr, res
    assert "Traceback" not in res.stderr and "Fatal Python error" not in res.stderr, res
    assert left == {"code": 1, "threads": []}, f"DDS threads outlived the command: {left}"
