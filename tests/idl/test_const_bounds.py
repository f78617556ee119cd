"""A string constant longer than its bounded type (issue 9, defect 3): NASA's RAPID IDL has
`const String16 K = "ATHLETE_HEADING_RAD";` (19 characters) and RTI's compiler accepts it.
rapidgen warns (RG0406), keeps the whole value, and fails only under -W error."""
from __future__ import annotations

import json
import subprocess
import sys

from tests.helpers import rapidgen

IDL = """module rapid {
  typedef string<16> String16;
  const String16 ATHLETE_HEADING = "ATHLETE_HEADING_RAD";
  const string<4> SHORT = "ok";
  struct Pose { String16 frame; };
};
"""


def _write(tmp_path):
    path = tmp_path / "athlete.idl"
    path.write_text(IDL, encoding="utf-8")
    return str(path)


def test_over_bound_constant_is_a_located_warning_and_keeps_its_value(tmp_path):
    path = _write(tmp_path)
    res = rapidgen("ir", "--no-loc", path)
    assert res.code == 0, res.err
    assert "athlete.idl:3:36: warning[RG0406]: string of 19 characters exceeds the bound of 'string<16>'" in res.err
    assert res.err.count("RG0406") == 1  # "ok" fits string<4>
    assert '"ATHLETE_HEADING_RAD"' in res.out


def test_generated_python_constant_holds_the_whole_string(tmp_path):
    out = tmp_path / "out"
    res = rapidgen("generate", _write(tmp_path), "-o", str(out), "--package", "athlete_types")
    assert res.code == 0, res.err
    assert "warning[RG0406]" in res.err
    # imported as a user would, in a child (the package stays out of this process)
    code = "import athlete_types.rapid as r, json; print(json.dumps(r.ATHLETE_HEADING))"
    child = subprocess.run([sys.executable, "-c", code], cwd=out / "python", capture_output=True, text=True,
                           timeout=120)
    assert child.returncode == 0, child.stderr
    assert json.loads(child.stdout) == "ATHLETE_HEADING_RAD"


def test_warnings_as_errors_fails_and_writes_nothing(tmp_path):
    out = tmp_path / "out"
    res = rapidgen("generate", _write(tmp_path), "-o", str(out), "-W", "error")
    assert res.code == 1 and "error[RG0406]" in res.err
    assert not out.exists()


def test_the_warning_can_be_silenced(tmp_path):
    res = rapidgen("ir", _write(tmp_path), "-W", "no-RG0406")
    assert res.code == 0 and res.err == ""


def test_a_default_over_its_bound_stays_an_error(tmp_path):
    """Only const declarations are lenient (RTI accepts them); a @default value that does
    not fit its member's bounded string is an error, located at the value."""
    path = tmp_path / "d.idl"
    path.write_text('module m {\n  typedef string<4> S4;\n'
                    '  struct P { @default("toolong") S4 name; @default("ok") string<4> b; };\n};\n',
                    encoding="utf-8")
    res = rapidgen("ir", str(path))
    assert res.code == 1, res.err
    assert "d.idl:3:23: error[RG0402]: string of 7 characters exceeds the bound of 'string<4>'" in res.err
    assert "RG0406" not in res.err and res.err.count("error[") == 1  # "ok" fits
    # the same value as a const is still only the warning
    path.write_text('module m {\n  typedef string<4> S4;\n  const S4 K = "toolong";\n};\n', encoding="utf-8")
    res = rapidgen("ir", str(path))
    assert res.code == 0 and "d.idl:3:16: warning[RG0406]" in res.err and "RG0402" not in res.err
