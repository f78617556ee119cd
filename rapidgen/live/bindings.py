"""An asset's DDS types, tables and QoS, generated from its descriptor into a temporary
folder and imported from there: what a live tool needs to read and write the asset's
topics, with no generated package installed (works from the rapidgen wheel alone)."""
from __future__ import annotations

import contextlib
import importlib
import io
import re
import sys
import tempfile
from dataclasses import dataclass, field
from types import ModuleType
from typing import TYPE_CHECKING, Protocol

from rapidgen.diagnostics import DiagnosticSink

if TYPE_CHECKING:
    from cyclonedds.qos import Qos


class RapidQosLike(Protocol):
    """What the live tools use of a generated package's RapidQos (a class imported at run
    time from the temporary folder, so the checker cannot see it)."""
    topics: tuple[str, ...]

    def key(self, topic: str) -> str: ...
    def writer(self, topic: str) -> Qos: ...
    def reader(self, topic: str) -> Qos: ...
    def publisher(self, topic: str | None = None) -> Qos: ...
    def subscriber(self, topic: str | None = None) -> Qos: ...
    def cyclonedds_config(self, transport: str | None = None) -> str: ...


@dataclass
class AssetBindings:
    package: str
    folder: str  # the temporary output folder (python/, qos/)
    rapid: ModuleType  # the generated `rapid` module: rapid.Command, rapid.Ack, ...
    tables: dict  # the generated asset_tables module's literals (ASSET, COMMANDS, ...)
    qos: RapidQosLike  # the package's RapidQos
    _tmp: object = field(default=None, repr=False)

    def type_class(self, scoped: str):
        """rapid::ext::arc::GpsConfig -> the generated class."""
        parts = scoped.split("::")
        if parts[0] != "rapid":
            raise KeyError(scoped)
        mod = self.rapid
        for name in parts[1:-1]:
            mod = getattr(mod, name, None) or importlib.import_module(f"{mod.__name__}.{name}")
        return getattr(mod, parts[-1])

    def transport_file(self, transport: str) -> str:
        return self.qos.cyclonedds_config(transport)


def load_bindings(descriptor: str, sink: DiagnosticSink, prefix: str = "rapidlive") -> AssetBindings | None:
    """Generate python+qos for the descriptor and import the package (None after
    diagnostics in sink). Needs cyclonedds (the generated types import it)."""
    from rapidgen.generate import load_inputs, render, write_outputs

    inputs = load_inputs([descriptor], [], sink)
    if inputs is None or inputs.asset is None:
        return None
    name = re.sub(r"\W", "_", inputs.asset.spec.name).lower()
    package = f"{prefix}_{name}"[:60]
    per_lang = render(inputs, ["python", "qos"], sink, package)
    if per_lang is None:
        return None
    tmp = tempfile.TemporaryDirectory(prefix="rapidgen-live-")
    with contextlib.redirect_stdout(io.StringIO()):  # its per-target lines mean nothing here
        written = write_outputs(tmp.name, per_lang, sink)
    if not written:
        tmp.cleanup()
        return None
    pydir = f"{tmp.name}/python"
    sys.path.insert(0, pydir)
    try:
        importlib.invalidate_caches()
        for mod in [m for m in sys.modules if m == package or m.startswith(package + ".")]:
            del sys.modules[mod]  # a second asset of the same name in this process
        rapid = importlib.import_module(f"{package}.rapid")
        tables_mod = importlib.import_module(f"{package}.asset_tables")
        qos = importlib.import_module(f"{package}.qos").RapidQos()
    finally:
        sys.path.remove(pydir)
    tables = {k: v for k, v in vars(tables_mod).items() if k.isupper()}
    return AssetBindings(package, tmp.name, rapid, tables, qos, tmp)
