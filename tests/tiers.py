"""What each test file needs, as pytest markers (docs/testing.md).

    dds       starts DDS participants or processes (loopback or a namespace)
    compiler  builds C++ or Rust (cmake, g++, cargo)
    browser   drives Debian's chromium
    netns     makes private network namespaces (root)
    slow      a campaign that takes tens of seconds even alone (kill at every write, 10 MB inputs)

A test takes the marks of the most specific entry that names it (the test, its file, else its
folder).
The fast tier (`bash scripts/test --fast`) is every test with none of these marks; it runs
with the compilers, chromium and DDS made unusable (scripts/test), so an entry missing here
fails there rather than slowing the tier down unseen. tests/unit/test_tiers.py checks that
every test file is covered.
"""
from __future__ import annotations

NEEDS: dict[str, frozenset[str]] = {k: frozenset(v.split()) for k, v in {
    # folders
    "tests/asset/": "",
    "tests/cdr/": "",
    "tests/conformance/": "dds",
    "tests/cpp/": "compiler",
    "tests/cpp_client/": "compiler dds",
    "tests/cpp_runtime/": "compiler dds",
    "tests/diff/": "",
    "tests/e2e/": "dds compiler",
    "tests/field/": "dds netns",
    "tests/fuzz/": "",
    "tests/golden/": "",
    "tests/monitor/": "dds browser",
    "tests/negative/": "",
    "tests/python_backend/": "dds",
    "tests/qos/": "dds",
    "tests/record/": "dds",
    "tests/ros2/": "dds",
    "tests/runtime/": "dds",
    "tests/rust/": "compiler",
    "tests/rust_runtime/": "compiler",
    "tests/secure/": "dds compiler netns",
    "tests/hostile/": "",
    "tests/specs/": "",
    "tests/spy/": "dds",
    "tests/streams/": "compiler dds",
    "tests/unit/": "",
    "tests/idl/": "",
    "tests/cmd/": "dds",
    # files that differ from their folder
    "tests/cdr/test_cyclone.py": "dds",
    "tests/cpp/test_fastdds_limits.py": "compiler dds",
    "tests/cpp/test_interop.py": "compiler dds",
    "tests/diff/test_live.py": "dds",
    "tests/diff/test_docs.py": "dds",
    "tests/monitor/test_foxglove_live.py": "dds",
    "tests/monitor/test_state.py": "",
    "tests/negative/test_corpus.py": "slow",
    "tests/python_backend/test_namer.py": "",
    "tests/python_backend/test_determinism.py": "",
    "tests/qos/test_spec.py": "",
    "tests/qos/test_fastdds.py": "compiler dds",
    "tests/qos/test_cyclone.py": "dds compiler",
    "tests/rust/test_interop.py": "compiler dds",
    "tests/rust/test_interop_cpp.py": "compiler dds",
    "tests/rust_runtime/test_broken.py": "compiler dds",
    "tests/rust_runtime/test_config_republish.py": "compiler dds",
    "tests/rust_runtime/test_dds_bridge.py": "compiler dds",
    "tests/rust_runtime/test_interop_client.py": "compiler dds",
    "tests/rust_runtime/test_streams.py": "compiler dds",
    "tests/rust_runtime/test_texts.py": "",
    "tests/runtime/test_spec_cases.py": "",
    "tests/runtime/test_texts.py": "",
    "tests/hostile/test_generated_parse.py": "dds",
    "tests/hostile/test_live_bridge.py": "dds",
    "tests/hostile/test_live_conform.py": "dds",
    "tests/hostile/test_live_helpers.py": "dds compiler",
    "tests/hostile/test_live_spy.py": "dds",
    "tests/hostile/test_writer.py::test_kill_at_every_mutation_leaves_exactly_old_or_new_output": "slow",
    # hypothesis and mutation campaigns: the full run has them, the fast tier not
    "tests/hostile/test_escaping.py::test_arbitrary_descriptor_text_generates_safe_files": "slow",
    "tests/hostile/test_escaping.py::test_arbitrary_idl_text_generates_safe_code": "slow",
    "tests/asset/test_fuzz.py::test_mutated_seeds": "slow",
    "tests/qos/test_spec.py::test_mutated_libraries_give_diagnostics_never_exceptions": "slow",
    "tests/hostile/test_input_bounds.py::test_large_descriptor_stops_while_parsing_and_says_why": "slow",
    "tests/hostile/test_frontend_bounds.py::test_many_unknown_names": "slow",
}.items()}

MARKS = ("dds", "compiler", "browser", "netns", "slow")


def needs(nodeid: str) -> frozenset[str] | None:
    """The marks of a test (its node id: a path relative to the root, '/'-separated, then
    '::name', parameters ignored), or None when no entry covers it."""
    test = nodeid.split("[", 1)[0]
    path = test.split("::", 1)[0]
    for key in (test, path):
        if key in NEEDS:
            return NEEDS[key]
    folder = path.rsplit("/", 1)[0] + "/"
    while folder:
        if folder in NEEDS:
            return NEEDS[folder]
        folder = folder[:-1].rpartition("/")[0]
        folder = folder + "/" if folder else ""
    return None
