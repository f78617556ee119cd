"""Serialize / deserialize ns/op of the generated C++ codec beside fastddsgen's code and memcpy.

    .venv/bin/python bench/cpp_codec.py [--keep DIR]

Builds (Release, -O2) one program from generated/rapid/cpp (rapidgen's code) and from
fastddsgen's output for the same types: the RAPID IDL printed here in IDL 4 form (structs
flattened base-first, keys as @key, inside `module fdg` so both sets link into one
program). Cases: Command with 3 arguments, JointSample with 64 joints, a 1 MB
ImageSensorSample. Prints figures only; needs cmake, g++, libfastcdr-dev and fastddsgen
(Debian package `fastddsgen`). The program also checks both codes write the same bytes.
"""
from __future__ import annotations

import argparse
import glob
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from rapidgen.diagnostics import DiagnosticSink  # noqa: E402
from rapidgen.idl.load import load_idl  # noqa: E402
from rapidgen.model import ir  # noqa: E402

WANTED = ("rapid::Command", "rapid::JointSample", "rapid::ImageSensorSample")


def spell(t: ir.Type) -> str:
    if isinstance(t, ir.Primitive):
        return ir.IDL_SPELLING[t.name]
    if isinstance(t, ir.String):
        return f"string<{t.bound}>" if t.bound else "string"
    if isinstance(t, ir.Sequence):
        return f"sequence<{spell(t.element)}, {t.bound}>" if t.bound else f"sequence<{spell(t.element)}>"
    if isinstance(t, ir.TypeRef):
        return "fdg::" + t.name
    raise ValueError(f"not printable here: {t}")


def declarator(t: ir.Type, name: str) -> str:
    if isinstance(t, ir.Array):
        return f"{spell(t.element)} {name}" + "".join(f"[{d}]" for d in t.dims)
    return f"{spell(t)} {name}"


def idl4(model: ir.Model) -> dict[str, str]:
    """One IDL 4 file per wanted type (fastddsgen names its output after the file), the
    shared declarations in Base.idl."""
    needed: set[str] = set()
    for name in WANTED:
        _need(model, ir.TypeRef(name, "struct"), needed)
    lines = ["module fdg {"]
    for d in model.declarations:
        if d.scoped_name in needed and d.scoped_name not in WANTED:
            lines += _decl(model, d)
    lines.append("};")
    files = {"Base.idl": "\n".join(lines) + "\n"}
    for name in WANTED:
        d = model.get(name)
        files[name.split("::")[-1] + ".idl"] = '#include "Base.idl"\nmodule fdg {\n' + "\n".join(_decl(model, d)) + "\n};\n"
    return files


def _need(model: ir.Model, t: ir.Type, out: set[str]) -> None:
    """The declarations a type needs (what Base.idl must hold)."""
    if isinstance(t, (ir.Sequence, ir.Array)):
        _need(model, t.element, out)
    if not isinstance(t, ir.TypeRef) or t.name in out:
        return
    out.add(t.name)
    d = model.get(t.name)
    if isinstance(d, ir.Typedef):
        _need(model, d.type, out)
    elif isinstance(d, ir.Struct):
        for m in model.all_members(d):
            _need(model, m.type, out)
    elif isinstance(d, ir.Union):
        _need(model, d.discriminator, out)
        for c in d.cases:
            _need(model, c.member.type, out)


def _decl(model: ir.Model, d: ir.Declaration) -> list[str]:
    *mods, name = d.scoped_name.split("::")
    head = " ".join(f"module {m} {{" for m in mods)
    tail = " ".join("};" for _ in mods)
    if isinstance(d, ir.Typedef):
        body = f"typedef {declarator(d.type, name)};"
    elif isinstance(d, ir.Enum):
        body = f"enum {name} {{ " + ", ".join(e.name for e in d.enumerators) + " };"
    elif isinstance(d, ir.Union):
        cases = " ".join(
            ("default: " if c.is_default else "") + " ".join(f"case {lab}:" for lab in c.labels) + f" {declarator(c.member.type, c.member.name)};"
            for c in d.cases)
        body = f"union {name} switch ({spell(d.discriminator)}) {{ {cases} }};"
    elif isinstance(d, ir.Struct):
        top = {k.split(".")[0] for k in d.keys}
        members = " ".join(("@key " if m.name in top else "") + declarator(m.type, m.name) + ";"
                           for m in model.all_members(d))
        body = f"struct {name} {{ {members} }};"
    else:
        return []
    return [f"{head} {body} {tail}"]


TOOLS = {"cmake": "cmake", "g++": "g++", "fastddsgen": "fastddsgen"}  # tool: its Debian package
# the program's columns after the case name (bench/cpp_codec/bench.cpp prints them)
COLUMNS = ("bytes", "ser_ours", "ser_fdg", "de_ours", "de_fdg", "memcpy", "ser_x", "de_x")


class BuildFailed(Exception):
    """The C++ program could not be built (the message says what to look at)."""


def missing_tools() -> list[str]:
    """'tool (apt: package)' for each build tool not on PATH."""
    return [f"{tool} (apt: {pkg})" for tool, pkg in TOOLS.items() if shutil.which(tool) is None]


def rapid_model() -> ir.Model:
    """The RAPID IDL set (specs/rapid), the types both programs are built from."""
    sink = DiagnosticSink()
    model, _ = load_idl(sorted(glob.glob(str(ROOT / "specs/rapid/*.idl"))), [str(ROOT / "specs/rapid")], sink)
    if model is None:
        raise BuildFailed("specs/rapid/*.idl did not load: " + "; ".join(str(d) for d in sink.errors))
    return model


def build(work: Path) -> Path:
    """Writes fastddsgen's code and a CMake project into `work`, builds it (Release, -O2)
    and returns the program's path; raises BuildFailed."""
    missing = missing_tools()
    if missing:
        raise BuildFailed("not installed: " + ", ".join(missing))
    model = rapid_model()
    work.mkdir(parents=True, exist_ok=True)
    fdg = work / "fastddsgen"
    fdg.mkdir(exist_ok=True)
    for name, text in idl4(model).items():
        (fdg / name).write_text(text, encoding="utf-8")
    res = subprocess.run(["fastddsgen", "-replace", "-d", str(fdg), "-I", str(fdg),
                          *[str(fdg / n) for n in ("Base.idl", "Command.idl", "JointSample.idl", "ImageSensorSample.idl")]],
                         capture_output=True, text=True, cwd=fdg, stdin=subprocess.DEVNULL)
    if res.returncode != 0:
        raise BuildFailed(f"fastddsgen failed:\n{res.stdout}{res.stderr}")
    (work / "CMakeLists.txt").write_text(f"""cmake_minimum_required(VERSION 3.16)
project(cpp_codec_bench CXX)
set(CMAKE_CXX_STANDARD 17)
set(CMAKE_BUILD_TYPE Release)
find_package(fastcdr REQUIRED)
file(GLOB FDG_SOURCES {fdg}/*.cxx)
list(FILTER FDG_SOURCES EXCLUDE REGEX "PubSubTypes")
add_executable(bench {ROOT}/bench/cpp_codec/bench.cpp {ROOT}/generated/rapid/cpp/src/types.cpp ${{FDG_SOURCES}})
target_include_directories(bench PRIVATE {ROOT}/generated/rapid/cpp/include {fdg})
target_compile_options(bench PRIVATE -O2)
target_link_libraries(bench PRIVATE fastcdr)
""", encoding="utf-8")
    for cmd in (["cmake", "-S", str(work), "-B", str(work / "build")], ["cmake", "--build", str(work / "build"), "-j2"]):
        res = subprocess.run(cmd, capture_output=True, text=True, stdin=subprocess.DEVNULL)
        if res.returncode != 0:
            raise BuildFailed(f"{' '.join(cmd)} failed:\n{res.stdout[-3000:]}{res.stderr[-6000:]}")
    return work / "build" / "bench"


def parse(text: str) -> tuple[dict[str, dict[str, float]], list[str]]:
    """The program's output as {case: {column: value}}, and its other lines (the header
    aside: a round trip or a byte comparison that failed)."""
    rows: dict[str, dict[str, float]] = {}
    notes: list[str] = []
    for line in text.splitlines():
        fields = line.split()
        if not fields or fields[0] == "type":
            continue
        try:
            values = [float(f.rstrip("x")) for f in fields[-len(COLUMNS):]]
        except ValueError:
            values = []
        if len(fields) > len(COLUMNS) and len(values) == len(COLUMNS):
            rows[" ".join(fields[:-len(COLUMNS)])] = dict(zip(COLUMNS, values))
        else:
            notes.append(line)
    return rows, notes


def measure(program: Path) -> tuple[dict[str, dict[str, float]], list[str]]:
    """One run of the program (each figure the best of its 5 loops), parsed."""
    res = subprocess.run([str(program)], capture_output=True, text=True, stdin=subprocess.DEVNULL)
    rows, notes = parse(res.stdout)
    if res.returncode != 0:
        notes.append(f"{program} exited {res.returncode}: {res.stderr.strip()[-500:]}")
    return rows, notes


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--keep", help="build in this folder and keep it")
    args = ap.parse_args()
    work = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="cpp_codec_"))
    try:
        program = build(work)
    except BuildFailed as err:
        print(err)
        return 1
    print("ns/op, best of 5 runs; ser/de x: fastddsgen's time over ours (above 1: ours is faster)")
    sys.stdout.flush()
    return subprocess.run([str(program)]).returncode


if __name__ == "__main__":
    sys.exit(main())
