"""Usage errors exit 2 (README), and the help names what can be asked for."""
import pytest

from rapidgen import backends
from tests.helpers import rapidgen


def test_unknown_target_is_a_usage_error(tmp_path):
    res = rapidgen("generate", "specs/assets/k10.yaml", "--lang", "python,foo", "-o", str(tmp_path / "out"))
    assert res.code == 2
    assert "unknown or unavailable target 'foo'" in res.err and "python, qos" in res.err
    assert not (tmp_path / "out").exists()  # nothing generated for the known target either


def test_empty_target_list_is_a_usage_error(tmp_path):
    assert rapidgen("generate", "specs/assets/k10.yaml", "--lang", ",", "-o", str(tmp_path)).code == 2


@pytest.mark.parametrize("args", [["--help"], ["generate", "--help"]])
def test_help_lists_the_targets(args):
    res = rapidgen(*args)
    assert res.code == 0
    for name in backends.known():
        assert name in res.out


def test_package_help_names_the_real_defaults():
    out = rapidgen("generate", "--help").out
    assert "rapid_types" in out and "crate" not in out


@pytest.mark.parametrize("args", [["cmd", "specs/assets/k10.yaml", "Admin", "noOp"], ["spy", "--once"],
                                  ["conform", "specs/assets/k10.yaml"]])
@pytest.mark.parametrize("domain", ["233", "-1", "x"])
def test_a_domain_outside_0_232_is_a_usage_error(args, domain):
    res = rapidgen(*args, "--domain", domain)
    assert res.code == 2 and "0..232" in res.err
