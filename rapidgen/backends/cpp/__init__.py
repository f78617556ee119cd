"""C++ target: a CMake package of C++17 types with XCDR1 encode/decode and Fast DDS 2.9
topic types; for an asset also its constants (asset.hpp) and its bridge on the C++ runtime
(bridge/: tables, typed handler classes and glue, main, the user's handlers.cpp).

    generate(model, asset, options) -> [GeneratedFile]

The package (and CMake target, and include folder) is named like the Python one:
options.package, else `rapid_` + the asset name, else `rapid_types`. docs/cpp-backend.md
has the layout and the mapping rules; view.py (types), asset.py (constants) and bridge.py
(the bridge) decide everything the templates print.
"""
from __future__ import annotations

import re
from typing import TYPE_CHECKING

from rapidgen.backends.base import QOS_LIBRARY, GeneratedFile, Options, check_output, notice
from rapidgen.backends.typewalk import Unsupported
from rapidgen.backends.cpp.view import Builder, PackageView, UnsupportedInput
from rapidgen.backends.escape import cmake_name, cpp_str
from rapidgen.backends.support import support_file
from rapidgen.backends.templating import render
from rapidgen.model.ir import Model

if TYPE_CHECKING:
    from rapidgen.asset import LoadedAsset

NAME = "cpp"
DEFAULT_PACKAGE = "rapid_types"

__all__ = ["NAME", "DEFAULT_PACKAGE", "UnsupportedInput", "companions", "embed", "generate", "needs",
           "package_for", "view"]

BRIDGE = "bridge"  # the asset's bridge sources, beside the types (bridge.py)


def needs(asset: "LoadedAsset | None") -> frozenset[str]:
    """An asset package's bridge carries its Fast DDS profiles (the qos target's)."""
    return frozenset({QOS_LIBRARY}) if asset is not None else frozenset()


def companions(asset: "LoadedAsset | None") -> tuple[str, ...]:
    return ("qos",) if asset is not None else ()


def embed(files: list[GeneratedFile], other: dict[str, list[GeneratedFile]]) -> list[GeneratedFile]:
    """The qos target's Fast DDS XML built into the bridge (bridge/profiles.cpp)."""
    target = f"{BRIDGE}/profiles.cpp"
    if not any(f.path == target for f in files):
        return files
    from rapidgen.backends.cpp import bridge
    xml = next((f.content for f in other.get("qos", []) if f.path == bridge.PROFILES_XML), None)
    if xml is None:
        return files
    lines = [cpp_str(line) for line in xml.splitlines(keepends=True)]
    return [GeneratedFile(f.path, _with_profiles(f.content, lines)) if f.path == target else f for f in files]


def _with_profiles(content: str, lines: list[str]) -> str:
    """profiles.cpp with the XML's lines in place of its empty literal (a marker no escaped
    text can hold: cpp_comment breaks every `/*`)."""
    return content.replace(PROFILES_MARK, "\n    ".join(lines) + ";", 1)


PROFILES_MARK = '"" /* the profiles: rapidgen embeds the qos target\'s XML here */;'


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
    files = [GeneratedFile("CMakeLists.txt", render("cpp", "CMakeLists.txt.j2", p=p, bridge=asset is not None)),
             GeneratedFile("cmake/Config.cmake.in", render("cpp", "Config.cmake.in.j2", p=p)),
             GeneratedFile(f"{inc}/cdr.hpp", support_file("cpp", "cdr.hpp", p.header)),
             GeneratedFile(f"{inc}/dds.hpp", support_file("cpp", "dds.hpp", p.header)),
             GeneratedFile(f"{inc}/types.hpp", render("cpp", "types.hpp.j2", p=p)),
             GeneratedFile(f"{inc}/topics.hpp", render("cpp", "topics.hpp.j2", p=p)),
             GeneratedFile("src/types.cpp", render("cpp", "types.cpp.j2", p=p))]
    if asset is not None:
        from rapidgen.backends.cpp import asset as asset_tables, bridge  # an asset's only (their classes)
        try:
            a = asset_tables.build(asset, b)
            v = bridge.build(asset, b, p.package, a)
        except Unsupported as exc:
            raise UnsupportedInput([(str(exc), exc.loc or asset.spec.at("name"))]) from None
        files.append(GeneratedFile(f"{inc}/asset.hpp", render("cpp", "asset.hpp.j2", p=p, a=a)))
        files += [GeneratedFile(f"{BRIDGE}/{name}", render("cpp", f"bridge/{name}.j2", p=p, v=v))
                  for name in ("handlers.hpp", "dispatch.cpp", "tables.cpp", "main.cpp", "profiles.cpp")]
        files.append(GeneratedFile(f"{BRIDGE}/handlers.cpp", render("cpp", "bridge/handlers.cpp.j2", p=p, v=v),
                                   user_owned=True))
    check_output(files, asset)
    return sorted(files, key=lambda f: f.path)
