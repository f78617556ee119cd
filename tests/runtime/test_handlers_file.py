"""The handlers module is the user's: written once, never touched by regeneration; the
tables and the bridge are regenerated."""
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).parents[2]


def _generate(out: Path) -> None:
    res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", "specs/assets/k10.yaml", "--lang", "python",
                          "-o", str(out)], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr


def test_regeneration_leaves_the_handler_file_byte_identical(tmp_path):
    _generate(tmp_path)
    pkg = tmp_path / "python" / "rapid_k10red"
    handlers = pkg / "handlers.py"
    stub = handlers.read_bytes()
    assert b'raise CommandFailed("not implemented")' in stub and b"def pan_tilt_camera_point_camera" in stub
    edited = stub.replace(b'raise CommandFailed("not implemented")', b"return 'done'", 1) + b"\n# mine\n"
    handlers.write_bytes(edited)
    tables = pkg / "asset_tables.py"
    tables.write_text("spoiled")
    _generate(tmp_path)
    assert handlers.read_bytes() == edited
    assert tables.read_text() != "spoiled"  # generated files are rewritten
    handlers.unlink()  # deleting it brings fresh stubs back
    _generate(tmp_path)
    assert handlers.read_bytes() == stub
