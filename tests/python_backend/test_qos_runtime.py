"""The QoS runtime, rapid_runtime.qos, through a generated package's `<package>/qos.py` (its
RapidQos with the package's default folder; template templates/python/qos.py.j2).

Robonaut 2's bindings and QoS files are generated into a temporary folder
(`rapidgen generate specs/assets/robonaut2.yaml --lang python,qos -o OUT`); then, for every
topic of OUT/qos/topics.json, RapidQos must return exactly what Cyclone's QoS provider
returns for the topic's profile key, and the config topics must carry RAPID's
RapidConfigQos (rapid-protocol.md section 6: reliable, transient-local, keep last 1).
No DDS participant is created here (the QoS provider only reads XML).
"""
from __future__ import annotations

import importlib.util
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.python_backend.fill import REPO

PACKAGE = "rapid_robonaut2"


def _generate(out: Path, langs: str, spec: str = "specs/assets/robonaut2.yaml") -> Path:
    res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", spec, "--lang", langs, "-o", str(out)],
                         cwd=REPO, capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stdout + res.stderr
    return out


def _load_runtime(path: Path, name: str):
    """The generated qos.py as a stand-alone module (it imports nothing of its package)."""
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def out(tmp_path_factory) -> Path:
    return _generate(tmp_path_factory.mktemp("r2") / "out", "python,qos")


@pytest.fixture(scope="module")
def runtime(out):
    return _load_runtime(out / "python" / PACKAGE / "qos.py", "rapidgen_test_r2_qos")


@pytest.fixture(scope="module")
def topic_map(out) -> dict:
    return json.loads((out / "qos" / "topics.json").read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def provider(out, topic_map):
    from cyclonedds.qos_provider import QosProvider

    return QosProvider(str(out / "qos" / topic_map["files"]["dds_xml"]))


def test_every_topic_gets_exactly_what_the_qos_provider_gives_for_its_profile(out, runtime, topic_map, provider):
    qos = runtime.RapidQos(out / "qos")
    entries = topic_map["topics"]
    assert len(entries) >= 10
    assert qos.topics == tuple(e["topic"] for e in entries)
    for e in entries:
        topic, key = e["topic"], e["key"]
        assert key == f"RapidQosLibrary::{e['profile']}"
        assert qos.key(topic) == key
        assert qos.writer(topic) == provider.get_datawriter_qos(key), topic
        assert qos.reader(topic) == provider.get_datareader_qos(key), topic
        assert qos.publisher(topic) == provider.get_publisher_qos(key), topic
        assert qos.subscriber(topic) == provider.get_subscriber_qos(key), topic
    # without a topic: the first topic's profile (what scripts/demo_live.py has always used)
    assert qos.publisher() == provider.get_publisher_qos(entries[0]["key"])
    assert qos.subscriber() == provider.get_subscriber_qos(entries[0]["key"])


def test_config_topics_are_rapid_config_qos(out, runtime, topic_map):
    from cyclonedds.core import Policy

    qos = runtime.RapidQos(out / "qos")
    configs = [e for e in topic_map["topics"] if e["role"] == "config"]
    assert {"rapid_agent_config", "rapid_command_config", "rapid_joint_config"} <= {e["topic"] for e in configs}
    for e in configs:
        assert e["profile"] == "RapidConfigQos", e
        for side in (qos.writer(e["topic"]), qos.reader(e["topic"])):
            assert isinstance(side[Policy.Reliability], Policy.Reliability.Reliable), (e["topic"], side)
            assert side[Policy.Durability] == Policy.Durability.TransientLocal, (e["topic"], side)
            assert side[Policy.History] == Policy.History.KeepLast(1), (e["topic"], side)


def test_publisher_and_subscriber_are_in_the_asset_partition(out, runtime):
    from cyclonedds.core import Policy

    qos = runtime.RapidQos(out / "qos")
    assert (qos.asset, qos.partition, qos.library) == ("Robonaut2", "Robonaut2", "RapidQosLibrary")
    assert qos.publisher()[Policy.Partition] == Policy.Partition(["Robonaut2"])
    assert qos.subscriber()[Policy.Partition] == Policy.Partition(["Robonaut2"])


def test_package_finds_its_own_qos_files(out):
    """`from <package>.qos import RapidQos; RapidQos()` finds the QoS files the asset package
    carries (<package>/qos_files, package data: they survive `pip install`), the same
    files as OUT/qos."""
    code = ("from rapid_robonaut2.qos import RapidQos\n"
            "q = RapidQos()\n"
            "print(q.qos_dir)\n"
            "print(q.writer('rapid_command'))\n")
    env = dict(os.environ, PYTHONPATH=str(out / "python"), PYTHONDONTWRITEBYTECODE="1")
    env.pop("CYCLONEDDS_URI", None)
    res = subprocess.run([sys.executable, "-c", code], cwd=out, env=env, capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr[-3000:]
    where, writer = res.stdout.splitlines()[:2]
    own = out / "python" / PACKAGE / "qos_files"
    assert Path(where) == own.resolve()
    for rel in ("topics.json", "dds-xml/rapid_qos.xml", "cyclonedds/local.xml"):
        assert (own / rel).read_bytes() == (out / "qos" / rel).read_bytes(), rel
    assert "KeepAll" in writer and "Reliable" in writer  # RAPID's command QoS


def test_without_a_qos_target_the_module_works_given_a_path(out, tmp_path):
    alone = _generate(tmp_path / "alone", "python")
    assert not (alone / "qos").exists()
    runtime = _load_runtime(alone / "python" / PACKAGE / "qos.py", "rapidgen_test_r2_alone_qos")
    assert runtime.RapidQos().writer("rapid_command") == runtime.RapidQos(out / "qos").writer("rapid_command")
    # Types alone (IDL, no asset) carry no QoS files: the error says where it looked.
    types_only = tmp_path / "types"
    res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", "specs/rapid/Ack.idl", "-I", "specs/rapid",
                          "--lang", "python", "-o", str(types_only)], cwd=REPO, capture_output=True, text=True,
                         timeout=120)
    assert res.returncode == 0, res.stderr
    runtime = _load_runtime(types_only / "python" / "rapid_types" / "qos.py", "rapidgen_test_types_alone_qos")
    with pytest.raises(runtime.QosFilesMissing) as missing:
        runtime.RapidQos()
    assert isinstance(missing.value, FileNotFoundError)
    text = str(missing.value)
    assert str(types_only / "qos") in text and "--lang python,qos" in text and "RapidQos('OUT/qos')" in text
    qos = runtime.RapidQos(str(out / "qos"))  # another output's qos folder, given explicitly
    assert qos.writer("rapid_agent_config") == runtime.RapidQos(out / "qos").writer("rapid_agent_config")


def test_unknown_topic_is_a_clear_error(out, runtime):
    qos = runtime.RapidQos(out / "qos")
    for call in (qos.writer, qos.reader, qos.publisher, qos.subscriber, qos.key):
        with pytest.raises(runtime.UnknownTopic) as err:
            call("rapid_agent_confg")
        assert isinstance(err.value, LookupError) and isinstance(err.value, runtime.RapidQosError)
        assert "'rapid_agent_confg' is not in" in str(err.value)
        assert "did you mean 'rapid_agent_config'?" in str(err.value)
    with pytest.raises(runtime.UnknownTopic):
        qos.writer(None)


def _qos_copy(out: Path, tmp_path: Path) -> Path:
    folder = tmp_path / "qos"
    shutil.copytree(out / "qos", folder)
    return folder


def test_missing_or_broken_files_are_clear_errors(out, runtime, tmp_path):
    folder = _qos_copy(out, tmp_path)
    (folder / "dds-xml" / "rapid_qos.xml").unlink()
    with pytest.raises(runtime.QosFilesMissing, match=r"names dds-xml/rapid_qos\.xml, which is not in"):
        runtime.RapidQos(folder)

    (folder / "dds-xml" / "rapid_qos.xml").write_text("<dds><qos_library", encoding="utf-8")
    with pytest.raises(runtime.RapidQosError, match="QoS provider cannot load"):
        runtime.RapidQos(folder)

    for broken in ("{not json", "[]", '{"topics": []}', '{"topics": [{"topic": "x"}], "files": {}}'):
        (folder / "topics.json").write_text(broken, encoding="utf-8")
        with pytest.raises(runtime.RapidQosError, match="is not a rapidgen topic map"):
            runtime.RapidQos(folder)

    (folder / "topics.json").unlink()
    with pytest.raises(runtime.QosFilesMissing, match="no topics.json in"):
        runtime.RapidQos(folder)


def test_no_topics_means_no_default_group_qos(out, runtime, tmp_path):
    folder = _qos_copy(out, tmp_path)
    data = json.loads((folder / "topics.json").read_text(encoding="utf-8"))
    data["topics"] = []
    (folder / "topics.json").write_text(json.dumps(data), encoding="utf-8")
    qos = runtime.RapidQos(folder)
    with pytest.raises(runtime.RapidQosError, match="lists no topics"):
        qos.publisher()


def test_cyclonedds_config_names_the_generated_transport_files(out, runtime):
    qos = runtime.RapidQos(out / "qos")
    local = qos.cyclonedds_config()
    assert Path(local) == out / "qos" / "cyclonedds" / "local.xml"
    assert qos.cyclonedds_config("wan") == str(out / "qos" / "cyclonedds" / "wan.xml")
    with pytest.raises(runtime.RapidQosError, match="no transport 'moon'"):
        qos.cyclonedds_config("moon")
    from tests.python_backend.live_peer import loopback_refusal

    assert loopback_refusal("file://" + local) is None


def test_runtime_is_static_code(tmp_path, out):
    """Only the header and the package name differ between two assets' qos.py."""
    k10 = _generate(tmp_path / "k10", "python", "specs/assets/k10.yaml")
    mine = (out / "python" / PACKAGE / "qos.py").read_text(encoding="utf-8")
    theirs = (k10 / "python" / "rapid_k10red" / "qos.py").read_text(encoding="utf-8")
    assert mine.startswith("# generated by rapidgen from specs/assets/robonaut2.yaml; do not edit\n")
    assert mine.split("\n", 1)[1].replace(PACKAGE, "PKG") == theirs.split("\n", 1)[1].replace("rapid_k10red", "PKG")


def _generate_idl(tmp_path: Path, source: str) -> dict[str, str]:
    from rapidgen.backends import python
    from rapidgen.backends.base import Options
    from rapidgen.diagnostics import DiagnosticSink
    from rapidgen.idl.load import load_idl

    (tmp_path / "q.idl").write_text(source, encoding="utf-8")
    sink = DiagnosticSink()
    model, _ = load_idl([str(tmp_path / "q.idl")], [str(tmp_path)], sink)
    assert model is not None, [d.message for d in sink.diagnostics]
    return {f.path: f.content for f in python.generate(model, None, Options(source="q.idl"))}


def test_an_idl_module_named_qos_does_not_shadow_the_runtime(tmp_path):
    files = _generate_idl(tmp_path, "module QoS { struct S { long x; }; };\nmodule m { const long qos = 1; };\n")
    assert "rapid_types/qos.py" in files
    assert "rapid_types/QoS_/__init__.py" in files and "rapid_types/QoS/__init__.py" not in files
    assert '"QoS_"' in files["rapid_types/__init__.py"]
    assert "from .._idl.q import qos\n" in files["rapid_types/m/__init__.py"]  # only the root is reserved


def test_a_global_declaration_named_qos_does_not_shadow_the_runtime(tmp_path):
    files = _generate_idl(tmp_path, "const long qos = 1;\n")
    assert "from ._idl.q import qos as qos_\n" in files["rapid_types/__init__.py"]
    assert '"qos_"' in files["rapid_types/__init__.py"]


def test_the_package_module_is_the_runtimes_with_its_default_folder(out):
    """qos.py holds no QoS code of its own: its classes are rapid_runtime.qos's; the runtime's
    RapidQos needs a folder or a package to find one; every package requires the runtime."""
    from rapid_runtime import qos as runtime_qos
    package = _load_runtime(out / "python" / PACKAGE / "qos.py", "rapidgen_test_r2_qos_thin")
    assert issubclass(package.RapidQos, runtime_qos.RapidQos)
    assert package.UnknownTopic is runtime_qos.UnknownTopic and package.QosFilesMissing is runtime_qos.QosFilesMissing
    assert package.RapidQos().qos_dir == str((out / "python" / PACKAGE / "qos_files").resolve())
    with pytest.raises(runtime_qos.QosFilesMissing, match="no qos folder"):
        runtime_qos.RapidQos()
    assert runtime_qos.RapidQos(out / "qos").writer("rapid_command") == package.RapidQos().writer("rapid_command")
    for pyproject in (out / "python" / "pyproject.toml", Path(REPO) / "generated/rapid/python/pyproject.toml"):
        assert '"rapid-runtime>=0.1,<0.2"' in pyproject.read_text(encoding="utf-8"), pyproject
