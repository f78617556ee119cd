"""Every generated C++ package in generated/ builds warning-free (-Wall -Wextra -Werror,
optimized: -O1, conftest.RELEASE).

The RAPID set's and K10's packages are built by the session fixture (conftest.py). The seeds'
types libraries are built once per run, with their bridges, in the seeds' build
(tests/cpp_runtime/build.py seed_types: the package's own CMakeLists on the run's `rapidgen
generate` output, the bytes of generated/<seed>, test_committed_generated_tree_is_current);
a package that build leaves out (RAPIDGEN_CPP_SEEDS, a target that is not a seed) is built
here, one CMake build of its own."""
from __future__ import annotations

import pytest

from tests.cpp.conftest import ROOT, _cmake
from tests.cpp_runtime import build as B

BUILT_BY_FIXTURE = {"rapid", "k10"}
# (spec-oddity is not a robot: the spec cases' tables, whose tables.cpp the C++ spec driver
# builds warning-free in tests/cpp_runtime; its package is the seeds' generator's output)
PACKAGES = sorted(p.parent.parent.name for p in (ROOT / "generated").glob("*/cpp/CMakeLists.txt")
                  if not p.parent.parent.name.startswith("spec-"))


def test_every_target_of_the_project_has_a_cpp_package():
    assert BUILT_BY_FIXTURE < set(PACKAGES) and len(PACKAGES) >= 7


@pytest.mark.parametrize("name", [p for p in PACKAGES if p not in BUILT_BY_FIXTURE])
def test_generated_package_builds_warning_free(name, tmp_path, tmp_path_factory):
    if name in B.chosen_seeds():
        assert B.seed_types(tmp_path_factory, name).exists()
        return
    _cmake(ROOT / "generated" / name / "cpp", tmp_path / "build")
    assert list((tmp_path / "build").glob("*.a")) or list((tmp_path / "build").glob("*.so"))
