"""C++ target: a CMake package of C++17 types with XCDR1 encode/decode and Fast DDS 2.9
topic types.

    generate(model, asset, options) -> [GeneratedFile]

The package (and CMake target, and include folder) is named like the Python one:
options.package, else `rapid_` + the asset name, else `rapid_types`. docs/cpp-backend.md
has the layout and the mapping rules; view.py decides everything the templates print.
"""
from __future__ import annotations

import re
from typing import TYPE_CHECKING

from rapidgen.backends.base import (NO_NEEDS, GeneratedFile, Options, check_output, embed_nothing, no_companions,
                                   notice)
from rapidgen.backends.cpp import asset as asset_tables
from rapidgen.backends.typewalk import Unsupported
from rapidgen.backends.cpp.view import Builder, PackageView, UnsupportedInput
from rapidgen.backends.escape import cmake_name
from rapidgen.backends.templating import render
from rapidgen.model.ir import Model

if TYPE_CHECKING:
    from rapidgen.asset import LoadedAsset

NAME = "cpp"
DEFAULT_PACKAGE = "rapid_types"

__all__ = ["NAME", "DEFAULT_PACKAGE", "UnsupportedInput", "companions", "embed", "generate", "needs",
           "package_for", "view"]

companions, embed = no_companions, embed_nothing


def needs(asset: "LoadedAsset | None") -> frozenset[str]:
    return NO_NEEDS


def package_for(asset: "LoadedAsset | None", options: Options) -> str:
    if options.package:
        return cmake_name(options.package)
    if asset is not None:
        return cmake_name("rapid_" + (re.sub(r"[^a-z0-9]+", "_", asset.spec.name.lower()).strip("_") or "asset"))
    return DEFAULT_PACKAGE


def view(model: Model, asset: "LoadedAsset | None", options: Options) -> tuple[PackageView, Builder]:
    b = Builder(model, package_for(asset, options))
    p = b.build(notice(options.source), options.source)
    return p, b


def generate(model: Model, asset: "LoadedAsset | None", options: Options) -> list[GeneratedFile]:
    """Raises UnsupportedInput when the model uses what the cpp target cannot express."""
    p, b = view(model, asset, options)
    inc = f"include/{p.package}"
    files = [GeneratedFile("CMakeLists.txt", render("cpp", "CMakeLists.txt.j2", p=p)),
             GeneratedFile("cmake/Config.cmake.in", render("cpp", "Config.cmake.in.j2", p=p)),
             GeneratedFile(f"{inc}/cdr.hpp", render("cpp", "cdr.hpp.j2", header=p.header)),
             GeneratedFile(f"{inc}/dds.hpp", render("cpp", "dds.hpp.j2", header=p.header)),
             GeneratedFile(f"{inc}/types.hpp", render("cpp", "types.hpp.j2", p=p)),
             GeneratedFile(f"{inc}/topics.hpp", render("cpp", "topics.hpp.j2", p=p)),
             GeneratedFile("src/types.cpp", render("cpp", "types.cpp.j2", p=p))]
    if asset is not None:
        try:
            a = asset_tables.build(asset, b)
        except Unsupported as exc:
            raise UnsupportedInput([(str(exc), exc.loc or asset.spec.at("name"))]) from None
        files.append(GeneratedFile(f"{inc}/asset.hpp", render("cpp", "asset.hpp.j2", p=p, a=a)))
    check_output(files, asset)
    return sorted(files, key=lambda f: f.path)
