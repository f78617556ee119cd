"""LIVE: every RAPID message type published and received over Cyclone DDS on loopback.

A subscriber process and a publisher process (tests/python_backend/live_peer.py), both
using the committed bindings in generated/rapid/python, both started with CYCLONEDDS_URI
set to tests/interop/cyclonedds-loopback.xml (127.0.0.1 only, no multicast), DDS domain
43, a partition unique to this run. Each received sample is compared field by field with
the value the publisher wrote, and the type name the remote writer announced in discovery
must be the IDL scoped name (`rapid::Command`). Every wait has a timeout.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import pytest

from tests.python_backend.fill import GENERATED_RAPID, REPO, Filler, differences, message_types, plain, rapid_model

LOOPBACK_XML = os.path.join(REPO, "tests", "interop", "cyclonedds-loopback.xml")
DOMAIN = 43
TIMEOUT = 40.0


def _env() -> dict[str, str]:
    env = dict(os.environ)
    env["CYCLONEDDS_URI"] = "file://" + LOOPBACK_XML
    env["PYTHONPATH"] = os.pathsep.join([REPO, GENERATED_RAPID])
    env["PYTHONDONTWRITEBYTECODE"] = "1"  # leave no __pycache__ in generated/
    return env


def _peer(role: str, partition: str) -> subprocess.Popen:
    cmd = [sys.executable, "-m", "tests.python_backend.live_peer", role, "--domain", str(DOMAIN),
           "--partition", partition, "--timeout", str(TIMEOUT - 10)]
    return subprocess.Popen(cmd, cwd=REPO, env=_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def _finish(proc: subprocess.Popen, deadline: float) -> tuple[str, str]:
    try:
        return proc.communicate(timeout=max(1.0, deadline - time.monotonic()))
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate(timeout=10)
        pytest.fail(f"live peer {proc.args[3]} timed out\nstdout: {out[-2000:]}\nstderr: {err[-2000:]}")


def test_every_rapid_message_over_loopback():
    assert os.path.isfile(os.path.join(GENERATED_RAPID, "rapid_types", "__init__.py")), \
        "generated/rapid is missing: run `rapidgen check --fix`"
    partition = f"rapidgen-python-live-{os.getpid()}-{time.time_ns()}"
    started = time.monotonic()
    deadline = started + TIMEOUT
    sub = _peer("sub", partition)
    pub = None
    try:
        pub = _peer("pub", partition)
        sub_out, sub_err = _finish(sub, deadline)  # the subscriber first: its output is the big one
        pub_out, pub_err = _finish(pub, deadline)  # the publisher leaves once the subscriber is gone
    finally:
        for proc in (sub, pub):
            if proc is not None and proc.poll() is None:
                proc.kill()
                proc.communicate(timeout=10)
    elapsed = time.monotonic() - started
    assert pub.returncode == 0 and "PUBLISHED" in pub_out, f"publisher failed:\n{pub_out}\n{pub_err[-3000:]}"
    assert sub.returncode == 0 and "DONE" in sub_out, f"subscriber failed:\n{sub_out[-3000:]}\n{sub_err[-3000:]}"

    received = {r["type"]: r for r in (json.loads(line) for line in sub_out.splitlines() if line.startswith("{"))}
    sys.path.insert(0, GENERATED_RAPID)
    sys.dont_write_bytecode, saved = True, sys.dont_write_bytecode
    try:
        model = rapid_model()
        filler = Filler(model)
        messages = message_types(model)
        assert len(messages) == 15
        problems = []
        for s in messages:
            got = received.get(s.scoped_name)
            if got is None:
                problems.append(f"{s.scoped_name}: nothing received")
                continue
            if got["type_name"] != [s.scoped_name]:
                problems.append(f"{s.scoped_name}: remote writer announced type {got['type_name']}")
            problems += [f"{s.scoped_name}{d}" for d in differences(plain(filler.message(s)), got["value"])]
    finally:
        sys.path.remove(GENERATED_RAPID)
        sys.dont_write_bytecode = saved
    assert not problems, "\n".join(problems[:50])
    print(f"\nlive: {len(messages)} RAPID message types over loopback in {elapsed:.2f} s")
