"""The C++ asset runtime (runtime/cpp) and the bridge `rapidgen generate --lang cpp` writes
on it: built with -Wall -Wextra -Werror (conftest.py, once per session), the GoogleTest
suite (protocol logic, K10's generated tables and glue, the simulator, synthetic pictures)
plain and under ThreadSanitizer, the user's handlers.cpp kept across regeneration, and
K10's generated bridge run without --simulate (its stubs answer "not implemented"), and
the protocol specification's cases (runtime/spec/cases) replayed by the GoogleTest driver
test_spec_cases.cpp. The bridges pass `rapidgen conform`: tests/conformance/test_cpp_asset.py.
Domains 40-49."""
from __future__ import annotations

import json
import os
import re
import struct
import subprocess
import sys
import zlib
from pathlib import Path

import pytest
import yaml

from rapidgen.protocol_cases import load_cases
from tests.cpp_runtime import build as B
from tests.runtime.live import SEEDS, env_for, python_dir

DOMAIN = 46  # the stub bridge below (tests/conformance/test_cpp_asset.py: 40-45)
SPEC = "Spec*"  # the spec cases' tests in `logic` (Spec/Case.Replays/..., SpecCases.Loaded)
# Cases where the C++ runtime answers otherwise than the case (and the Python runtime) says,
# by "file:name", each with the difference; the test fails when one of them passes (then
# it leaves this list) as when any other case fails.
# Cases the C++ runtime is known to answer otherwise (each with why); empty: none.
CPP_DIFFERS: dict[str, str] = {}


@pytest.fixture(scope="session")
def spec_cases_json(tmp_path_factory) -> Path:
    """Every case of runtime/spec/cases as the drivers read them (rapidgen.protocol_cases)."""
    path = tmp_path_factory.mktemp("spec-cases") / "cases.json"
    path.write_text(json.dumps({"cases": load_cases()}, ensure_ascii=False), encoding="utf-8")
    return path


def _gtest(program: Path, cases: Path, *args: str, timeout: float, **env: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(program), *args], capture_output=True, text=True, timeout=timeout,
                          env=dict(os.environ, RAPID_SPEC_CASES=str(cases), **env))


def test_logic_suite_passes(runtime_build):
    res = subprocess.run([str(runtime_build / "logic"), "--gtest_brief=1", f"--gtest_filter=-{SPEC}"],
                         capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stdout[-6000:] + res.stderr[-3000:]
    ran = re.search(r"\[==========\] (\d+) tests", res.stdout)
    assert ran and int(ran.group(1)) >= 45, res.stdout[-2000:]


def test_cpp_runtime_replays_the_spec_cases(runtime_build, spec_cases_json, tmp_path):
    """Every case of runtime/spec/cases, replayed by the C++ runtime (test_spec_cases.cpp):
    a failing one is reported by file:line and name with what was expected and seen."""
    report = tmp_path / "report.json"
    res = _gtest(runtime_build / "logic", spec_cases_json, f"--gtest_filter={SPEC}", f"--gtest_output=json:{report}",
                 timeout=600)
    assert report.exists(), res.stdout[-3000:] + res.stderr[-3000:]
    tests = [t for suite in json.loads(report.read_text(encoding="utf-8"))["testsuites"] for t in suite["testsuite"]]
    loaded = [t for t in tests if t["name"] == "Loaded"]
    assert loaded and "failures" not in loaded[0], loaded
    cases = json.loads(spec_cases_json.read_text(encoding="utf-8"))["cases"]
    # (the driver prints a case as "file:line 'name'")
    by_place = {f"{c['file']}:{c['line']}": f"{c['file']}:{c['name']}" for c in cases}
    replayed = {by_place[t["value_param"].split(" ", 1)[0]]: t for t in tests
                if t.get("value_param", "").split(" ", 1)[0] in by_place}
    assert len(replayed) == len(cases), f"{len(replayed)} of {len(cases)} cases replayed\n{res.stdout[-3000:]}"
    failed = {key: t for key, t in replayed.items() if "failures" in t}
    unexpected = [f"{t['value_param']}:\n  " + "\n  ".join(f["failure"].split("\n", 2)[-1] for f in t["failures"])
                  for key, t in failed.items() if key not in CPP_DIFFERS]
    fixed = [key for key in CPP_DIFFERS if key in replayed and key not in failed]
    assert not unexpected, f"{len(unexpected)} of {len(cases)} cases fail in C++:\n" + "\n".join(unexpected)
    assert not fixed, f"these cases pass now: take them out of CPP_DIFFERS: {fixed}"
    assert res.returncode == (1 if failed else 0), res.stdout[-3000:] + res.stderr[-3000:]


def test_logic_suite_is_clean_under_thread_sanitizer(logic_under_tsan, spec_cases_json):
    """The logic suite and the spec cases (their outcomes are test_cpp_runtime_replays_the_spec_cases's
    to judge: here, no data race nor deadlock)."""
    known = ":".join(f"Spec/Case.Replays/{_gtest_name(k)}" for k in CPP_DIFFERS)
    res = _gtest(logic_under_tsan, spec_cases_json, "--gtest_brief=1", *([f"--gtest_filter=-{known}"] if known else []),
                 timeout=900, TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1")
    assert res.returncode == 0 and "ThreadSanitizer" not in res.stderr, res.stdout[-3000:] + res.stderr[-6000:]


def _gtest_name(key: str) -> str:
    """The GoogleTest name test_spec_cases.cpp gives the case "file:name" (test_name())."""
    file, _, name = key.partition(":")
    return re.sub(r"_+", "_", re.sub(r"[^A-Za-z0-9]", "_", f"{file.rsplit('.', 1)[0]}_{name}")).strip("_")


# ---- synthetic pictures: decoded here, independently of the encoder -------------------------------

def _png_pixels(data: bytes) -> tuple[int, int, int, bytes]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, head = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        assert struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])[0] == zlib.crc32(kind + body)
        if kind == b"IHDR":
            head = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    assert head is not None
    w, h, depth, colour = head[:4]
    assert depth == 8 and colour in (0, 2)
    raw = zlib.decompress(idat)  # checks the Adler-32 too
    px = 1 if colour == 0 else 3
    assert len(raw) == h * (1 + w * px) and all(raw[r * (1 + w * px)] == 0 for r in range(h))
    return w, h, px, raw


def _jpeg_blocks(data: bytes) -> tuple[int, int, int, int]:
    """(width, height, components, blocks decoded) of a baseline JPEG whose AC table holds
    only end-of-block: the scan is decoded with its own DC table."""
    assert data[:2] == b"\xff\xd8" and data[-2:] == b"\xff\xd9"
    pos, dc, size = 2, None, None
    while True:
        marker, n = data[pos + 1], struct.unpack(">H", data[pos + 2:pos + 4])[0]
        body = data[pos + 4:pos + 2 + n]
        if marker == 0xC0:
            _p, h, w, nc = struct.unpack(">BHHB", body[:6])
            size = (w, h, nc)
        elif marker == 0xC4 and body[0] == 0x00:
            counts, values, codes, code, k = body[1:17], body[17:], {}, 0, 0
            for length, count in enumerate(counts, start=1):
                for _ in range(count):
                    codes[(length, code)] = values[k]
                    code, k = code + 1, k + 1
                code <<= 1
            dc = codes
        elif marker == 0xDA:
            pos += 2 + n
            break
        pos += 2 + n
    assert dc is not None and size is not None
    scan = data[pos:-2].replace(b"\xff\x00", b"\xff")
    bits = "".join(f"{b:08b}" for b in scan)
    w, h, nc = size
    want, i, blocks = ((w + 7) // 8) * ((h + 7) // 8) * nc, 0, 0
    while blocks < want:
        length, code = 0, 0
        while (length, code) not in dc:
            code, length, i = (code << 1) | int(bits[i]), length + 1, i + 1
            assert length <= 16
        i += dc[(length, code)]  # the difference's magnitude bits
        assert bits[i] == "0"  # end of block: the AC table's one code
        i, blocks = i + 1, blocks + 1
    assert set(bits[i:]) <= {"1"} and len(bits) - i < 8  # padding only
    return w, h, nc, blocks


def test_synthetic_pictures_decode(runtime_build, tmp_path):
    res = subprocess.run([str(runtime_build / "logic"), "--gtest_filter=Images.*"], capture_output=True, text=True,
                         timeout=120, env=dict(os.environ, RAPID_IMAGES_OUT=str(tmp_path)))
    assert res.returncode == 0, res.stdout[-3000:]
    w, h, px, raw = _png_pixels((tmp_path / "rgb.png").read_bytes())
    assert (w, h, px) == (640, 480, 3)
    sky, ground = raw[1:4], raw[(h - 40) * (1 + 3 * w) + 1:][:3]
    assert sky[2] > sky[0] and ground[0] > ground[2]  # blue above, ochre below
    assert _png_pixels((tmp_path / "grey.png").read_bytes())[:3] == (37, 13, 1)
    assert _jpeg_blocks((tmp_path / "rgb.jpg").read_bytes())[:3] == (1360, 1024, 3)
    assert _jpeg_blocks((tmp_path / "grey.jpg").read_bytes())[:3] == (33, 17, 1)
    bmp = (tmp_path / "rgb.bmp").read_bytes()
    assert bmp[:2] == b"BM" and struct.unpack("<I", bmp[2:6])[0] == len(bmp) == 54 + 9 * ((21 * 3 + 3) & ~3)
    assert (tmp_path / "g.pgm").read_bytes() == b"P5\n5 3\n255\n" + (tmp_path / "g.pgm").read_bytes()[11:]


# ---- the user's handlers.cpp ----------------------------------------------------------------------

def _generate(descriptor: Path, out: Path) -> subprocess.CompletedProcess:
    res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(descriptor), "--lang", "cpp", "-o",
                          str(out)], cwd=B.ROOT, capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    return res


def test_regeneration_leaves_handlers_cpp_byte_identical(tmp_path):
    k10 = B.ROOT / "specs" / "assets" / "k10.yaml"
    _generate(k10, tmp_path / "out")
    handlers = tmp_path / "out" / "cpp" / "bridge" / "handlers.cpp"
    stub = handlers.read_bytes()
    assert stub.count(b'Result::failed("not implemented")') == 9  # every command the runtime does not answer
    assert b"do not edit" not in stub  # it is the user's
    _generate(k10, tmp_path / "out")
    assert handlers.read_bytes() == stub
    # the user's version survives regeneration, also when the descriptor changes
    mine = stub.replace(b'return ::rapid_runtime::Result::failed("not implemented");',
                        b'return ::rapid_runtime::Result::ok("mine");', 1) + b"// my notes\n"
    handlers.write_bytes(mine)
    changed = yaml.safe_load(k10.read_text(encoding="utf-8"))
    changed["idl"] = {k: str((k10.parent / v).resolve()) if isinstance(v, str) else [str((k10.parent / x).resolve())
                      for x in v] for k, v in changed["idl"].items()}
    changed["subsystem_types"][0]["commands"].append({"name": "wipeLens", "description": "clean the optics"})
    (tmp_path / "k10b.yaml").write_text(yaml.safe_dump(changed), encoding="utf-8")
    header = (tmp_path / "out" / "cpp" / "bridge" / "handlers.hpp").read_text(encoding="utf-8")
    res = _generate(tmp_path / "k10b.yaml", tmp_path / "out")
    assert handlers.read_bytes() == mine, res.stdout
    new_header = (tmp_path / "out" / "cpp" / "bridge" / "handlers.hpp").read_text(encoding="utf-8")
    assert "wipeLens" in new_header and "wipeLens" not in header
    # fresh stubs: delete the file
    handlers.unlink()
    _generate(tmp_path / "k10b.yaml", tmp_path / "out")
    assert b"wipeLens" in handlers.read_bytes()


# ---- the generated bridge program -------------------------------------------------------------------

def _bridge(seed_bridges, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(seed_bridges["k10"]), *args], capture_output=True, text=True, timeout=60,
                          env=B.dds_env())


def test_bridge_options(seed_bridges):
    if "k10" not in seed_bridges:
        pytest.skip("K10 not among RAPIDGEN_CPP_SEEDS")
    res = _bridge(seed_bridges, "--help")
    assert res.returncode == 0 and "--simulate" in res.stdout and "(default 0)" in res.stdout
    res = _bridge(seed_bridges, "--domian", "3")
    assert res.returncode == 2 and "unknown option --domian" in res.stderr and "usage:" in res.stderr
    res = _bridge(seed_bridges, "--domain", "-1")
    assert res.returncode == 2 and "bad value for --domain" in res.stderr
    res = _bridge(seed_bridges, "--transport", "nosuch", "--domain", str(DOMAIN), "--seconds", "0")
    assert res.returncode == 1 and "no participant profile rapid_nosuch" in res.stderr
    res = _bridge(seed_bridges, "--qos", "/nonexistent.xml", "--domain", str(DOMAIN), "--seconds", "0")
    assert res.returncode == 1 and "cannot load QoS profiles /nonexistent.xml" in res.stderr
    res = _bridge(seed_bridges, "--domain", str(DOMAIN), "--seconds", "0.2", "--transport", "local")
    assert res.returncode == 0, res.stderr
    assert res.stdout.splitlines() == ["bridge ready: asset K10Red, domain 46, partition K10Red", "bridge stopped"]


def _cmd(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "rapidgen", "cmd", str(B.ROOT / "specs" / "assets" / "k10.yaml"),
                           *args, "--domain", str(DOMAIN), "--source", "RapidWorkbench", "--timeout", "20"],
                          cwd=B.ROOT, env=env_for(python_dir("k10"), SEEDS["k10"]), capture_output=True, text=True,
                          timeout=120)


def test_generated_bridge_without_simulate_runs_the_stub_handlers(seed_bridges):
    """Without --simulate the bridge runs handlers.cpp as generated: the runtime answers its
    own commands, every other one COMPLETED/EXEC_FAILED "not implemented"; Admin/shutdown
    stops it cleanly."""
    pytest.importorskip("cyclonedds")
    if "k10" not in seed_bridges:
        pytest.skip("K10 not among RAPIDGEN_CPP_SEEDS")
    proc = subprocess.Popen([str(seed_bridges["k10"]), "--domain", str(DOMAIN), "--seconds", "120"],
                            env=B.dds_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "bridge ready: asset K10Red, domain 46, partition K10Red"
        res = _cmd("AccessControl", "requestControl")
        assert res.returncode == 0 and "COMPLETED OK  control granted to RapidWorkbench" in res.stdout, res
        res = _cmd("PanCam", "pointCamera", "pan=0.5")
        assert res.returncode == 1 and res.stdout.splitlines()[1:] == [
            "  EXECUTING", "  COMPLETED EXEC_FAILED  not implemented"], res.stdout + res.stderr
        res = _cmd("Admin", "echo", "text=hello")
        assert res.returncode == 0 and "COMPLETED OK  hello" in res.stdout, res.stdout + res.stderr
        res = _cmd("Admin", "shutdown")
        assert res.returncode == 0, res.stdout + res.stderr
        out, err = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            proc.terminate()
            proc.communicate(timeout=30)
    assert proc.returncode == 0 and out.strip() == "bridge stopped", (out, err[-2000:])


# ---- names and text C++ must not be handed raw --------------------------------------------------------

def test_hostile_descriptor_names_are_valid_cpp(tmp_path):
    """The bridge files of a hostile descriptor (build.hostile_descriptor): every name a
    usable, distinct C++ name, every text kept exactly. It compiles with -Werror and passes
    `rapidgen conform` in tests/conformance/test_cpp_asset.py."""
    (tmp_path / "h.yaml").write_text(yaml.safe_dump(B.hostile_descriptor(), allow_unicode=True), encoding="utf-8")
    _generate(tmp_path / "h.yaml", tmp_path / "out")
    hpp = (tmp_path / "out" / "cpp" / "bridge" / "handlers.hpp").read_text(encoding="utf-8")
    assert "class classHandler {" in hpp and "class Class_HandlerHandler {" in hpp
    assert "virtual ::rapid_runtime::Result delete_(::rapid_runtime::CommandContext& ctx, const ::std::string& ctx_, " \
           "float this_, ::std::int32_t my_arg, ::std::int64_t my_arg_, const ::rapid_runtime::Vec3d& arg_9lives, " \
           "const ::rapid_runtime::Mat33f& ber, bool assert_) = 0;" in hpp
    assert "Result class_Handler(" in hpp and "Result ClassHandler(" in hpp  # distinct names
    assert "Result HandlerSet_(" in hpp and "Result on_start(" in hpp  # the set's names stay the set's
    assert "const ::std::string& std, double rapid_runtime)" in hpp  # (every type is spelled from ::)
    tables = (tmp_path / "out" / "cpp" / "bridge" / "tables.cpp").read_text(encoding="utf-8")
    assert r'"a\"b"' in tables and r'"\?\?="' in tables and "-9223372036854775807LL - 1" in tables
    assert '"\\303\\234ber"' in tables  # the descriptor's name, exactly (UTF-8 bytes)
    assert '"Hostile \\"1\\" part"' in tables
    assert "*/" not in "".join(ln for ln in hpp.splitlines() if ln.lstrip().startswith("//"))
