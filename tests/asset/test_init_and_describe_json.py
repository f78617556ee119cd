"""`rapidgen init` writes a starter descriptor that validates as written and never
overwrites; `rapidgen describe --json` holds what describe prints."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.helpers import rapidgen

ROOT = Path(__file__).resolve().parents[2]


def test_init_writes_a_descriptor_that_validates_and_generates(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = rapidgen("init", "Scout")
    assert res.code == 0 and (tmp_path / "scout.yaml").is_file()
    text = (tmp_path / "scout.yaml").read_text()
    assert text.startswith("# Asset capability descriptor for Scout") and "name: Scout" in text
    res = rapidgen("validate", "scout.yaml")
    assert res.code == 0 and res.err == "" and "scout.yaml: valid (asset Scout" in res.out
    res = rapidgen("generate", "scout.yaml", "--lang", "python,qos", "-o", "out")
    assert res.code == 0 and (tmp_path / "out/python/rapid_scout/asset_tables.py").is_file()


def test_init_never_overwrites(tmp_path):
    target = tmp_path / "mine.yaml"
    target.write_text("my work\n")
    res = rapidgen("init", "Scout", "-o", str(target))
    assert res.code == 1 and "error[RG1910]" in res.err and "never overwrites" in res.err
    assert target.read_text() == "my work\n"
    link = tmp_path / "link.yaml"
    link.symlink_to(tmp_path / "elsewhere.yaml")  # a dangling link is not followed either
    res = rapidgen("init", "Scout", "-o", str(link))
    assert res.code == 1 and not (tmp_path / "elsewhere.yaml").exists()


@pytest.mark.parametrize("name", ["bad name", "1abc", "a/b", "x" * 65, ""])
def test_init_refuses_a_bad_name(tmp_path, monkeypatch, name):
    monkeypatch.chdir(tmp_path)
    res = rapidgen("init", name)
    assert res.code == 1 and "error[RG1910]" in res.err and list(tmp_path.iterdir()) == []


def test_init_into_a_missing_folder_is_a_located_error(tmp_path):
    res = rapidgen("init", "Scout", "-o", str(tmp_path / "no" / "such.yaml"))
    assert res.code == 1 and "error[RG1910]: cannot write" in res.err


def test_describe_json_holds_the_dictionary_and_telemetry():
    path = str(ROOT / "specs" / "assets" / "k10.yaml")
    res = rapidgen("describe", "--json", path)
    assert res.code == 0, res.err
    data = json.loads(res.out)
    assert (data["name"], data["kind"], data["domain"], data["partition"]) == ("K10Red", "rover", 0, "K10Red")
    text = rapidgen("describe", path).out
    types = {t["type"]: t for t in data["command_dictionary"]}
    point = next(c for c in types["PanTiltCamera"]["commands"] if c["name"] == "pointCamera")
    assert point["abortable"] and [p["name"] for p in point["parameters"]] == ["pan", "tilt"]
    assert point["parameters"][0] == {"name": "pan", "type": "RAPID_FLOAT", "unit": "rad", "min": -3.05,
                                          "max": 3.05, "allowed": [], "default": 0, "has_default": True,
                                          "description": ""}
    assert types["PanTiltCamera"]["subsystems"] == ["PanCam"]
    # every subsystem, command and topic describe prints is in the JSON, and no other
    assert [s["name"] for s in data["subsystems"]] == ["Admin", "Mobility", "Queue", "AccessControl", "PanCam",
                                                       "HazCams", "K10Native"]
    for t in data["command_dictionary"]:
        for c in t["commands"]:
            assert f"    {c['name']}" in text
    for p in data["publications"]:
        assert p["topic"] in text and p["qos"] in text
    agent = next(t for t in data["telemetry"] if t["kind"] == "agent")
    charge = next(v for v in agent["values"] if v["name"] == "batteryCharge")
    assert charge["warning"] == {"below": 30, "above": None} and charge["unit"] == "%"
    assert data["access_control"]["default"] == "deny"
    assert data["native"]["command"] == "nativeCommand"


def test_describe_json_of_a_bad_descriptor_is_diagnostics_only(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("version: 1\nasset: {name: X}\n")
    res = rapidgen("describe", "--json", str(bad))
    assert res.code == 1 and res.out == "" and "error[" in res.err
