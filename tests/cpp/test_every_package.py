"""Every generated C++ package in generated/ builds warning-free (-Wall -Wextra -Werror,
optimized: -O1, conftest.RELEASE).

The RAPID set's and K10's packages are built by the session fixture (conftest.py); the other
seeds' packages are built here, one CMake build each, in the run's temp folder."""
from __future__ import annotations

import pytest

from tests.cpp.conftest import ROOT, _cmake

BUILT_BY_FIXTURE = {"rapid", "k10"}
PACKAGES = sorted(p.parent.parent.name for p in (ROOT / "generated").glob("*/cpp/CMakeLists.txt"))


def test_every_target_of_the_project_has_a_cpp_package():
    assert BUILT_BY_FIXTURE < set(PACKAGES) and len(PACKAGES) >= 7


@pytest.mark.parametrize("name", [p for p in PACKAGES if p not in BUILT_BY_FIXTURE])
def test_generated_package_builds_warning_free(name, tmp_path):
    _cmake(ROOT / "generated" / name / "cpp", tmp_path / "build")
    assert list((tmp_path / "build").glob("*.a")) or list((tmp_path / "build").glob("*.so"))
