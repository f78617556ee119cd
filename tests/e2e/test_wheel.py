"""`pip install .` (not editable) gives a working rapidgen: templates, schemas, the QoS
library, the RAPID IDL and the runtimes' fixed files all ship in the wheel. Installed into a fresh venv that reuses
this environment's packages, then run from a folder outside the checkout."""
import shutil
import subprocess
import sys
import venv
from pathlib import Path

ROOT = Path(__file__).parents[2]


def test_installed_wheel_validates_and_generates_outside_the_checkout(tmp_path):
    # Build from a copy (symlinks resolved, as in a source distribution): building in the
    # checkout would leave build/ and *.egg-info behind.
    src = tmp_path / "src"
    shutil.copytree(ROOT / "rapidgen", src / "rapidgen", symlinks=False,
                    ignore=shutil.ignore_patterns("__pycache__"))
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, src / name)
    wheels = tmp_path / "wheels"
    subprocess.run([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "-w", str(wheels), str(src)],
                   check=True, timeout=300, capture_output=True)
    env_dir = tmp_path / "venv"
    venv.EnvBuilder(system_site_packages=False, with_pip=False).create(env_dir)
    py = env_dir / "bin" / "python"
    # Dependencies come from this environment's site-packages, the package itself from the wheel.
    site = next(Path(p) for p in sys.path if p.endswith("site-packages"))
    (next((env_dir / "lib").glob("python*")) / "site-packages" / "deps.pth").write_text(str(site) + "\n")
    wheel = next(wheels.glob("rapidgen-*.whl"))
    subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--target",
                    str(next((env_dir / "lib").glob("python*")) / "site-packages"), str(wheel)],
                   check=True, timeout=300, capture_output=True)
    work = tmp_path / "elsewhere"
    work.mkdir()
    # Without `idl: {rapid: ...}` the descriptor falls back to the RAPID IDL shipped in the wheel.
    text = (ROOT / "specs" / "assets" / "robonaut2.yaml").read_text()
    assert "idl:\n  rapid: ../rapid\n" in text
    (work / "r2.yaml").write_text(text.replace("idl:\n  rapid: ../rapid\n", ""))

    def run(*args):
        return subprocess.run([str(py), "-m", "rapidgen", *args], cwd=work, capture_output=True, text=True,
                              timeout=120)

    where = subprocess.run([str(py), "-c", "import rapidgen; print(rapidgen.__file__)"], cwd=work,
                           capture_output=True, text=True, timeout=60)
    assert str(ROOT) not in where.stdout, "the test must use the installed wheel, not the checkout"
    validated = run("validate", "r2.yaml")
    assert validated.returncode == 0, validated.stderr
    generated = run("generate", "r2.yaml", "--lang", "python,qos,cpp,rust", "-o", "out")
    assert generated.returncode == 0, generated.stderr
    assert (work / "out" / "python" / "pyproject.toml").is_file()
    # the runtimes' fixed files ship in the wheel too (rapidgen/support): each copy is its source
    for copy, source in ((next((work / "out" / "cpp" / "include").glob("*/cdr.hpp")), "runtime/cpp/support/cdr.hpp"),
                         (work / "out" / "rust" / "src" / "cdr.rs", "runtime/rust/rapid_support/src/cdr.rs")):
        assert copy.read_text().split("\n", 1)[1] == (ROOT / source).read_text()
    assert (work / "out" / "qos" / "cyclonedds" / "local.xml").is_file()
    ir = run("ir", str(ROOT / "specs" / "rapid" / "Ack.idl"), "-I", str(ROOT / "specs" / "rapid"))
    assert ir.returncode == 0 and '"rapid::Ack"' in ir.stdout
