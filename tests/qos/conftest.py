"""Fixtures of the QoS tier: generated files, the compiled Fast DDS probe, processes.

DDS rules for this folder: domain ids 60-79 only; every process has a timeout and is
killed at the end of its test; transports pinned to 127.0.0.1 (the generated `local`
transport, or `wan` with its interfaces set to 127.0.0.1); Fast DDS profiles disable the
SHM transport, and any /dev/shm/fastrtps_* file a test leaves is removed.
"""
from __future__ import annotations

import glob
import os
import shutil
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml

from rapidgen.backends import qos as qos_backend
from rapidgen.backends.base import Options
from rapidgen.diagnostics import DiagnosticSink
from rapidgen.generate import load_inputs, source_name
from rapidgen.qos import default_library, parse_qos

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
RAPID_IDL = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "specs" / "rapid").glob("*.idl"))
ROVER = "tests/qos/cases/rover.yaml"

# Domain ids of this tier (60-79), one per live test so that tests never see each other;
# every fixed port a test uses follows from its domain id (RTPS well-known ports, tcp_port).
DOMAIN_CYCLONE_LOCAL = 60          # test_cyclone: participant with the `local` config
DOMAIN_FASTDDS_QOS = 61            # test_fastdds: writers and readers of every profile
DOMAIN_TCP = 62                    # test_wan: Fast DDS TCP through a discovery server
DOMAIN_UDP_WAN = 63                # test_wan: Fast DDS and Cyclone DDS over UDP unicast
DOMAIN_NEGATIVE_TCP = 64           # test_wan: TCP clients without the server
DOMAIN_FASTDDS_EXCHANGE = {        # test_fastdds: local exchange, one per profile
    "RapidSampleQos": 65,
    "RapidReliableQos": 66,
}
LIVE_DOMAINS = [DOMAIN_CYCLONE_LOCAL, DOMAIN_FASTDDS_QOS, DOMAIN_TCP, DOMAIN_UDP_WAN, DOMAIN_NEGATIVE_TCP,
                *DOMAIN_FASTDDS_EXCHANGE.values()]
assert len(set(LIVE_DOMAINS)) == len(LIVE_DOMAINS) and all(60 <= d <= 79 for d in LIVE_DOMAINS), LIVE_DOMAINS
# qos_probe echo's COUNT when it should answer every ping until its SECONDS end: an echo written
# before its writer matched the pinger's reader is lost (volatile), so an echo that stopped at the
# pinger's own count could leave the pinger one short
ECHO_ALL = "100000"


def render(spec, asset_path: str | None) -> dict[str, str]:
    """Generate the qos target from the repository root: {relative path: content}."""
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        sink = DiagnosticSink()
        paths = [asset_path] if asset_path else RAPID_IDL
        inputs = load_inputs(paths, ["specs/rapid"], sink)
        assert inputs is not None, [str(d) for d in sink.diagnostics]
        files = qos_backend.render(spec, inputs.model, inputs.asset, Options(source=source_name(paths)))
    finally:
        os.chdir(cwd)
    return {f.path: f.content for f in files}


def write_tree(files: dict[str, str], out: Path) -> Path:
    for rel, content in files.items():
        target = out / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(content, encoding="utf-8")
    return out


def variant(**wan) -> object:
    """The shipped library with its `wan` transport changed (pinned interfaces, test ports)."""
    data = yaml.safe_load((ROOT / "specs" / "qos" / "rapid.yaml").read_text(encoding="utf-8"))
    w = data["transports"]["wan"]
    for key, value in wan.items():
        if key == "server_port":
            w["tcp"]["discovery_server"]["port"] = value
        elif key == "listening_port":
            w["tcp"]["listening_port"] = value
        else:
            w[key] = value
    sink = DiagnosticSink()
    spec = parse_qos(yaml.safe_dump(data, sort_keys=False), "variant.yaml", sink)
    assert spec is not None, [str(d) for d in sink.diagnostics]
    return spec


@pytest.fixture(scope="session")
def library():
    return default_library()


@pytest.fixture(scope="session")
def rover_files(library) -> dict[str, str]:
    return render(library, ROVER)


@pytest.fixture(scope="session")
def rover_dir(rover_files, tmp_path_factory) -> Path:
    return write_tree(rover_files, tmp_path_factory.mktemp("rover"))


def port_is_free(port: int) -> bool:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            s.bind(("127.0.0.1", port))
        except OSError:
            return False
    return True


def tcp_port(domain: int, offset: int) -> int:
    """A TCP port in the domain's RTPS block above its participant ports, else any free one."""
    port = 7400 + 250 * domain + 200 + offset
    if port_is_free(port):
        return port
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


# ------------------------------------------------------------------ processes


class Procs:
    """Processes started by one test: each with a deadline, all killed at teardown."""

    def __init__(self, tmp: Path) -> None:
        self.tmp = tmp
        self.items: list[tuple[subprocess.Popen, Path]] = []

    def start(self, name: str, args: list[str], timeout: float, env: dict | None = None,
              cwd: Path | None = None) -> subprocess.Popen:
        log = self.tmp / f"{name}.log"
        full_env = {**os.environ, **(env or {})}
        # `timeout` is the outer guard: the process dies even if this test is interrupted.
        proc = subprocess.Popen(["timeout", "-k", "2", str(timeout), *args], stdout=open(log, "w"),
                                stderr=subprocess.STDOUT, env=full_env, cwd=cwd, start_new_session=True)
        self.items.append((proc, log))
        return proc

    @staticmethod
    def wait(proc: subprocess.Popen, timeout: float) -> int:
        try:
            return proc.wait(timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            return proc.wait(5)

    def log(self, proc: subprocess.Popen) -> str:
        for p, log in self.items:
            if p is proc:
                return log.read_text(errors="replace")
        return ""

    def wait_for(self, proc: subprocess.Popen, text: str, timeout: float) -> bool:
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if text in self.log(proc):
                return True
            if proc.poll() is not None:
                return text in self.log(proc)
            time.sleep(0.02)
        return False

    def close(self) -> None:
        for proc, _ in self.items:
            if proc.poll() is None:
                try:
                    os.killpg(proc.pid, 15)
                except ProcessLookupError:
                    pass
                try:
                    proc.wait(3)
                except subprocess.TimeoutExpired:
                    os.killpg(proc.pid, 9)
                    proc.wait(3)


def _shm_files() -> set[str]:
    return set(glob.glob("/dev/shm/fastrtps_*")) | set(glob.glob("/dev/shm/sem.fastrtps_*"))


@pytest.fixture
def procs(tmp_path):
    before = _shm_files()
    p = Procs(tmp_path)
    yield p
    p.close()
    for leftover in _shm_files() - before:  # ours: SHM is off in the profiles, but be sure
        try:
            os.unlink(leftover)
        except OSError:
            pass


# ------------------------------------------------------------------ Fast DDS probe


@pytest.fixture(scope="session")
def probe(tmp_path_factory) -> Path:
    """tests/qos/cpp/qos_probe.cpp built once per session against Fast DDS 2.9."""
    if shutil.which("g++") is None or not Path("/usr/include/fastdds/dds/domain/DomainParticipant.hpp").exists():
        pytest.fail("g++ and libfastrtps-dev are needed (scripts/setup.sh installs them)")
    out = tmp_path_factory.mktemp("probe") / "qos_probe"
    res = subprocess.run(["g++", "-std=c++17", "-O1", "-o", str(out), str(HERE / "cpp" / "qos_probe.cpp"),
                          "-lfastrtps", "-lfastcdr"], capture_output=True, text=True, timeout=240)
    assert res.returncode == 0, res.stderr[-4000:]
    return out


PYTHON = sys.executable


def group_pids(pgid: int) -> set[int]:
    """Every live process of a process group (a test's process and its children)."""
    out = set()
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                if os.getpgid(int(entry)) == pgid:
                    out.add(int(entry))
            except OSError:
                pass
    return out


def udp_ports(pgid: int) -> set[int]:
    """Local UDP ports the processes of a group have bound (from `ss`)."""
    pids = group_pids(pgid)
    res = subprocess.run(["ss", "-H", "-u", "-a", "-n", "-p"], capture_output=True, text=True, timeout=10)
    ports = set()
    for line in res.stdout.splitlines():
        if any(f"pid={pid}," in line for pid in pids):
            local = line.split()[3]
            ports.add(int(local.rsplit(":", 1)[1]))
    return ports
