"""A domain whose RTPS ports lie in the host's ephemeral port range lets other domains in:
Fast DDS 2.9 announces no domain id, and Cyclone DDS reads the socket it sends from, whose
port the kernel picks from that range (runtime/cpp/include/rapid_runtime/ports.hpp). Seen in
CI: a conformance runner on one domain judged a C++ bridge on domain 133. Shown here in a
private network namespace whose ephemeral range is squeezed onto one of domain 133's ports,
then the C++ runtime's start-up warning, each side of the range. Domains 75 and 133 here are
inside the namespaces only."""
from __future__ import annotations

import shlex
import shutil
import subprocess
import sys

import pytest

from tests.conformance.harness import ROOT
from tests.cpp_runtime import build as B

pytest.importorskip("cyclonedds")
WARNING = "rapid_runtime: warning: domain 133's RTPS ports (40650-40699) lie in this host's ephemeral port range"


def _in_namespace(script: str, timeout: float) -> subprocess.CompletedProcess:
    if shutil.which("unshare") is None or shutil.which("ip") is None:
        pytest.fail("unshare and ip (util-linux, iproute2) are needed: this runs in a private network namespace")
    return subprocess.run(["unshare", "-n", "sh", "-ec", "ip link set lo up\n" + script], cwd=ROOT, env=B.dds_env(),
                          capture_output=True, text=True, timeout=timeout)


def test_the_suites_fast_dds_processes_on_the_host_use_domains_below_102():
    """Every Fast DDS participant the suite starts on the host's loopback (C++ bridges, tools
    and peers) is on a domain whose ports Linux's default range never hands out, so no Cyclone
    process of another test finds it (the CI failure this file is about)."""
    from tests.conformance.test_cpp_asset import DOMAINS as CPP_ASSETS
    from tests.cpp import test_fastdds_limits as limits, test_interop as cpp_interop
    from tests.cpp_client import test_broken as broken, test_fuzz as fuzz, test_interop as client
    from tests.cpp_runtime import test_cpp_runtime as runtime, test_handler_faults as faults, test_restart as restart
    from tests.cpp_runtime import test_stale_telemetry as stale
    from tests.field import test_restart as field_restart
    from tests.rust import test_interop_cpp as rust_cpp
    from tests.streams import test_setpoint_stream as streams
    used = {*broken.DOMAINS, fuzz.DOMAIN, client.CPP_BRIDGE_DOMAIN, client.PY_BRIDGE_DOMAIN, client.PARTITION_DOMAIN,
            limits.DOMAIN_FLOOD, limits.DOMAIN_LOAD, *CPP_ASSETS.values(), runtime.DOMAIN, restart.KILL_DOMAIN,
            restart.CROSS_DOMAIN, restart.CROSS_DOMAIN + 1, field_restart.CPP_RESEND_DOMAIN,
            cpp_interop.DOMAIN_CPP_TO_PY, cpp_interop.DOMAIN_PY_TO_CPP, rust_cpp.DOMAIN_RUST_TO_CPP,
            rust_cpp.DOMAIN_CPP_TO_RUST, streams.DOMAIN, streams.RIG_DOMAIN, streams.SEED_DOMAIN, *faults.DOMAINS,
            stale.DOMAIN, 27}  # (27: the bridge that refuses --break and rapid_cmd with no asset)
    assert sorted(d for d in used if d >= 102) == []


@pytest.mark.parametrize("ports, warned", [("40662 40679", True), ("50000 60999", False)])
def test_bridge_warns_of_a_domain_in_the_ephemeral_range(programs, ports, warned, tmp_path):
    res = _in_namespace(f"sysctl -qw net.ipv4.ip_local_port_range='{ports}'\n"
                        f"RAPID_STATE_DIR={shlex.quote(str(tmp_path))} "
                        f"exec {shlex.quote(str(programs['k10']))} --simulate --domain 133 --seconds 0", 60)
    assert res.returncode == 0, res.stderr[-2000:]
    assert (WARNING in res.stderr) == warned, res.stderr[-2000:]


@pytest.mark.parametrize("port, found", [(40666, True), (40667, False)])
def test_cyclone_runner_on_another_domain_finds_the_bridge_through_its_send_port(programs, tmp_path, port, found):
    """The hazard itself, so that the advice stays true: once the bridge on domain 133 runs,
    the only ephemeral port left is `port`. At 40666 (participant index 3's discovery port)
    the bridge sends its announcements; `rapidgen conform` on domain 75 is given it as its
    send port and finds the bridge. At 40667 (that index's user data port) it does not."""
    state = tmp_path / "state"
    state.mkdir()
    script = (f"sysctl -qw net.ipv4.ip_local_port_range='50000 60999'\n"
              f"RAPID_STATE_DIR={shlex.quote(str(state))} {shlex.quote(str(programs['k10']))} --simulate --domain 133 "
              f"--seconds 60 >/dev/null 2>&1 &\n"
              f"bridge=$!\nsleep 2\nrc=0\n"
              f"sysctl -qw net.ipv4.ip_local_port_range='{port} {port}'\n"
              f"{shlex.quote(sys.executable)} -m rapidgen conform specs/assets/k10.yaml --domain 75 --only CFG-01 --timeout 5 || rc=$?\n"
              f"kill $bridge\nwait $bridge || true\nexit $rc")
    res = _in_namespace(script, 120)
    assert ("found K10Red" in res.stdout) == found, res.stdout[-2000:] + res.stderr[-2000:]
    if not found:
        assert "no participant with K10Red's topics" in res.stderr, res.stderr[-2000:]
