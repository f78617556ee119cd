"""`rapidgen validate` and `rapidgen describe` from the command line."""
import difflib
from pathlib import Path

import pytest

from tests.asset.conftest import ROOT
from tests.helpers import rapidgen

GOLDEN = Path(__file__).resolve().parent / "golden"


@pytest.mark.parametrize("name", ["robonaut2", "eva-suit"])
def test_describe_output(name, update_golden, monkeypatch):
    monkeypatch.chdir(ROOT)
    res = rapidgen("describe", f"specs/assets/{name}.yaml")
    assert res.code == 0 and res.err == ""
    path = GOLDEN / f"{name}.describe.txt"
    if update_golden:
        path.write_text(res.out, encoding="utf-8")
    want = path.read_text(encoding="utf-8")
    if res.out != want:
        pytest.fail("".join(difflib.unified_diff(want.splitlines(True), res.out.splitlines(True),
                                                 path.name, "actual")))


def test_describe_shows_dictionary_and_telemetry(monkeypatch):
    monkeypatch.chdir(ROOT)
    out = rapidgen("describe", "specs/assets/k10.yaml").out
    for needle in ("Command dictionary", "PanTiltCamera: PanCam", "takePanorama  [abortable, suspendable]",
                   "left, right, stereo", "rapid_ext_arc_gps_sample", "rapid::ext::arc::GpsSample",
                   "rapid_imagesensor_sample-panCamLeft", "RapidSampleQos", "< 30", "Access control",
                   "Native passthrough"):
        assert needle in out, needle


def test_missing_file_is_a_clean_error(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = rapidgen("validate", "nope.yaml")
    assert res.code == 1
    assert res.err.startswith("nope.yaml:1:1: error[RG1001]: cannot read 'nope.yaml': No such file")
    assert "Traceback" not in res.err


def test_directory_is_a_clean_error(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "d.yaml").mkdir()
    res = rapidgen("describe", "d.yaml")
    assert res.code == 1 and "error[RG1001]: 'd.yaml' is a directory" in res.err


def test_validate_reports_every_file(monkeypatch):
    monkeypatch.chdir(ROOT)
    res = rapidgen("validate", "specs/assets/k10.yaml", "tests/asset/negative/duplicate-subsystem.yaml",
                   "tests/asset/negative/schema-bad-enum.yaml")
    assert res.code == 1
    assert "specs/assets/k10.yaml: valid" in res.out
    assert "duplicate-subsystem.yaml:6:12" in res.err and "schema-bad-enum.yaml:2:28" in res.err
    assert "rapidgen: 2 errors" in res.err


def test_warnings_can_be_silenced_or_promoted(monkeypatch):
    monkeypatch.chdir(ROOT)
    case = "tests/asset/negative/warn-partition-and-unused-type.yaml"
    assert rapidgen("validate", "-W", "no-RG1401", "-W", "no-RG1108", case).err == ""
    assert rapidgen("validate", "-W", "error", case).code == 1


@pytest.mark.parametrize("domain, warned", [(0, False), (101, False), (102, True), (214, True), (215, False),
                                            (232, False)])
def test_domain_in_the_ephemeral_port_band_is_warned_of(domain, warned, tmp_path, monkeypatch):
    """RG1403 exactly for the domains whose first 20 participants' ports meet 32768-60999
    (docs/qos.md, "Domain ids on one host"; runtime/cpp ports.hpp draws the same line)."""
    monkeypatch.chdir(ROOT)
    desc = tmp_path / "probe.yaml"
    desc.write_text(f"version: 1\nasset: {{name: Probe, kind: rover}}\ndds: {{domain: {domain}}}\n"
                    "subsystems: [{name: Admin}]\n", encoding="utf-8")
    res = rapidgen("validate", str(desc))
    assert res.code == 0 and ("warning[RG1403]" in res.err) == warned, res.err


def test_rapid_option_shipped_idl_and_missing_rapid_idl(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.yaml").write_text("version: 1\nasset: {name: A, kind: rover}\n")
    res = rapidgen("validate", "a.yaml")  # no specs/rapid above a tmp folder: the IDL shipped in the package
    assert res.code == 0 and "a.yaml: valid" in res.out, res.err
    res = rapidgen("validate", "--rapid", str(ROOT / "specs" / "rapid"), "a.yaml")
    assert res.code == 0, res.err
    (tmp_path / "empty").mkdir()
    res = rapidgen("validate", "--rapid", "empty", "a.yaml")
    assert res.code == 1 and "no RAPID IDL files in 'empty'" in res.err


def test_describe_of_an_invalid_descriptor_prints_nothing(monkeypatch):
    monkeypatch.chdir(ROOT)
    res = rapidgen("describe", "tests/asset/negative/duplicate-command.yaml")
    assert res.code == 1 and res.out == "" and "RG1101" in res.err


def test_the_documented_example_validates(tmp_path):
    text = (ROOT / "docs" / "asset-descriptor.md").read_text()
    example = text.split("```yaml\n", 1)[1].split("```", 1)[0]
    (tmp_path / "rover7.yaml").write_text(example)
    res = rapidgen("validate", "--rapid", str(ROOT / "specs" / "rapid"), str(tmp_path / "rover7.yaml"))
    assert res.code == 0 and res.err == "", res.err
