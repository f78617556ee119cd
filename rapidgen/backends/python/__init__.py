"""Python target: a pip-installable package of `cyclonedds.idl` classes.

    generate(model, asset, options) -> [GeneratedFile]

The package is named after the asset (`K10Red` -> `rapid_k10red`), or options.package,
or `rapid_types` for IDL alone. Every package carries the `qos` module (each topic's QoS
from the generated qos/ folder: rapid_runtime.qos with the package's default folder,
templates/python/qos.py.j2), so every package requires rapid-runtime. See view.py for the
layout and docs/python-backend.md for the mapping rules.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from rapidgen.backends.base import QOS_LIBRARY, GeneratedFile, Options, check_output, notice
from rapidgen.backends.python import namer
from rapidgen.backends.python.view import PackageView, UnsupportedInput, build
from rapidgen.backends.templating import render
from rapidgen.model.ir import Model

if TYPE_CHECKING:
    from rapidgen.asset import LoadedAsset

NAME = "python"
DEFAULT_PACKAGE = "rapid_types"

__all__ = ["NAME", "DEFAULT_PACKAGE", "UnsupportedInput", "companions", "embed", "generate", "needs", "package_for",
           "view"]


def needs(asset: "LoadedAsset | None") -> frozenset[str]:
    """An asset package carries its QoS files (the qos target's, which reads the library)."""
    return frozenset({QOS_LIBRARY}) if asset is not None else frozenset()


def companions(asset: "LoadedAsset | None") -> tuple[str, ...]:
    return ("qos",) if asset is not None else ()


def embed(files: list[GeneratedFile], other: dict[str, list[GeneratedFile]]) -> list[GeneratedFile]:
    """The qos target's files under <package>/qos_files/ (package data: RapidQos() works
    after `pip install`)."""
    if not other.get("qos"):
        return files
    from rapidgen.backends.python import asset_tables
    return asset_tables.with_qos_files(files, other["qos"])


def package_for(asset: "LoadedAsset | None", options: Options) -> str:
    if options.package:
        return namer.escape(namer.identifier(options.package), namer.KEYWORDS)
    if asset is not None:
        return namer.package_name(asset.spec.name)
    return DEFAULT_PACKAGE


def view(model: Model, asset: "LoadedAsset | None", options: Options) -> PackageView:
    return build(model, package_for(asset, options), options.source, notice(options.source))


def asset_files(model: Model, asset: "LoadedAsset", options: Options, pkg: PackageView) -> list[GeneratedFile]:
    """The asset's tables, handlers and bridge (asset_tables.py). The QoS files come in
    through embed() (a back end imports no other)."""
    from rapidgen.backends.python import asset_tables  # reads the descriptor's classes: assets only
    files = asset_tables.generate(asset, pkg.package, pkg.header)
    if asset.ros2 is not None:  # the descriptor maps the asset onto ROS 2
        from rapidgen.backends.python import ros2_files
        files += ros2_files.generate(asset, pkg.package, pkg.header)
    return files


def generate(model: Model, asset: "LoadedAsset | None", options: Options) -> list[GeneratedFile]:
    """Raises UnsupportedInput when the model uses what cyclonedds cannot encode."""
    pkg = view(model, asset, options)
    extras = asset_files(model, asset, options, pkg) if asset is not None else []
    runtime = None
    if extras:
        from rapidgen.backends.python import asset_tables
        runtime = asset_tables.runtime_view(pkg.package)  # package data: qos_files/
    files = [GeneratedFile("pyproject.toml", render("python", "pyproject.toml.j2", p=pkg.project, runtime=runtime)),
             GeneratedFile(pkg.support_path, render("python", "_support.py.j2", header=pkg.header)),
             GeneratedFile(pkg.qos.path, render("python", "qos.py.j2", q=pkg.qos))]
    files += [GeneratedFile(m.path, render("python", "module.py.j2", f=m)) for m in pkg.modules]
    files += extras
    check_output(files, asset)
    return sorted(files, key=lambda f: f.path)
