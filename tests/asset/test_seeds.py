"""The six seed robots validate cleanly, against rapidgen and against the bare JSON Schema."""
import json

import jsonschema
import pytest
import yaml

from rapidgen.asset.schema import schema
from tests.asset.conftest import ASSETS, ROOT, SEEDS
from tests.helpers import rapidgen


def test_all_six_validate(monkeypatch):
    monkeypatch.chdir(ROOT)
    res = rapidgen("validate", *(f"specs/assets/{s}.yaml" for s in SEEDS))
    assert res.code == 0, res.err
    assert res.err == ""  # not even a warning
    assert res.out.count(": valid (") == 6


def test_exactly_the_six_seeds_exist():
    assert sorted(p.stem for p in ASSETS.glob("*.yaml")) == sorted(SEEDS)


def test_schema_is_valid_draft_2020_12():
    jsonschema.Draft202012Validator.check_schema(schema())
    assert schema()["$schema"] == "https://json-schema.org/draft/2020-12/schema"


@pytest.mark.parametrize("name", SEEDS)
def test_seed_passes_the_bare_schema(name):
    # what an editor using the shipped schema sees: no errors on the seeds
    data = yaml.safe_load((ASSETS / f"{name}.yaml").read_text())
    errors = list(jsonschema.Draft202012Validator(schema()).iter_errors(json.loads(json.dumps(data))))
    assert not errors, [e.message for e in errors]


def test_schema_ships_in_the_package():
    from importlib import resources
    assert resources.files("rapidgen.asset").joinpath("asset.schema.json").is_file()


def test_seed_kinds(seed):
    kinds = {s: seed(s).spec.kind for s in SEEDS}
    assert kinds == {"k10": "rover", "chariot": "vehicle", "athlete": "walker", "eva-suit": "suit",
                     "robonaut2": "humanoid", "xarm2": "exoskeleton"}


def test_eva_suit_is_telemetry_only(seed):
    loaded = seed("eva-suit")
    spec = loaded.spec
    assert spec.subsystems == () and spec.native is None and "rapid_command_config" not in loaded.configs
    assert loaded.command_topic is None


def test_athlete_has_many_joints(seed):
    from rapidgen.asset.spec import JointTelemetry
    joints = [t for t in seed("athlete").spec.telemetry if isinstance(t, JointTelemetry)]
    assert sum(len(t.joints) for t in joints) == 42


def test_xarm2_joint_output_is_high_rate(seed):
    from rapidgen.asset.spec import JointTelemetry
    joint = next(t for t in seed("xarm2").spec.telemetry if isinstance(t, JointTelemetry))
    assert joint.rate >= 500 and set(joint.fields) >= {"anglePos", "angleVel", "torque"}
