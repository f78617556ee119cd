"""An asset's DDS types, tables and QoS: what a live tool (`cmd`, `conform`, `spy`) needs to
read and write the asset's topics. The one loader of live assets:

    load_bindings("specs/assets/k10.yaml", sink)   generated into a temporary folder and
                                                    imported from there (the rapidgen wheel
                                                    alone: no generated package installed)
    import_bindings("rapid_k10red")                 an installed generated package
"""
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


def find_type_class(bindings, type_name: str):
    """The generated class of a DDS type name ("rapid::Ack" or "rapid.Ack") in the first of
    `bindings` (AssetBindings) that has it, or None: the live tools read every type they know
    and skip (and report) the others."""
    scoped = type_name.replace(".", "::")
    for b in bindings:
        try:
            return b.type_class(scoped)
        except (KeyError, AttributeError, ImportError):
            continue
    return None


@dataclass
class AssetBindings:
    package: str
    folder: str  # the temporary output folder (python/, qos/)
    rapid: ModuleType  # the generated `rapid` module: rapid.Command, rapid.Ack, ...
    tables: dict  # the generated asset_tables module's literals (ASSET, COMMANDS, ...)
    qos: RapidQosLike  # the package's RapidQos
    qos_module: ModuleType | None = None  # the package's qos module (RapidQos, RapidQosError)
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
    try:
        return import_bindings(package, tmp.name, tmp)
    except BaseException:
        tmp.cleanup()
        raise


def import_bindings(package: str, folder: str | None = None, tmp: object = None) -> AssetBindings:
    """Import a generated package: from `folder`/python (a fresh import, replacing any
    earlier package of that name in this process), or as installed when folder is None.
    Raises ImportError, or the package's RapidQosError when its QoS files cannot be used."""
    pydir = f"{folder}/python" if folder is not None else None
    if pydir is not None:
        sys.path.insert(0, pydir)
    try:
        importlib.invalidate_caches()
        if pydir is not None:
            for mod in [m for m in sys.modules if m == package or m.startswith(package + ".")]:
                del sys.modules[mod]  # a second asset of the same name in this process
        rapid = importlib.import_module(f"{package}.rapid")
        tables_mod = importlib.import_module(f"{package}.asset_tables")
        qos_module = importlib.import_module(f"{package}.qos")
        qos = qos_module.RapidQos()
    finally:
        if pydir is not None:
            sys.path.remove(pydir)
    tables = {k: v for k, v in vars(tables_mod).items() if k.isupper()}
    return AssetBindings(package, folder or "", rapid, tables, qos, qos_module, tmp)
