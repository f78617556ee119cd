"""Rust target: a Cargo crate of Rust types with straight-line XCDR1 encode/decode.

    generate(model, asset, options) -> [GeneratedFile]

The crate is named like the Python package: options.package, else `rapid_` + the asset
name, else `rapid_types`. An asset's crate also holds src/asset.rs (topics, command
dictionary, computed configs). Features: `serde` (derives; src/serde_arrays.rs when a
member holds an array longer than 32) and `dds` (src/dds.rs, the RustDDS glue). docs/rust-backend.md has the layout and the mapping rules;
view.py decides everything the templates print.
"""
from __future__ import annotations

import re
from typing import TYPE_CHECKING

from rapidgen.backends.base import (QOS_LIBRARY, GeneratedFile, Options, check_output, embed_nothing,
                                   no_companions, notice)
from rapidgen.backends.escape import crate_name, rust_str
from rapidgen.backends.rust.view import Builder, CrateView, UnsupportedInput
from rapidgen.backends.support import support_file
from rapidgen.backends.templating import render
from rapidgen.model.ir import Model

if TYPE_CHECKING:
    from rapidgen.asset import LoadedAsset
    from rapidgen.backends.rust.asset import AssetView

NAME = "rust"
DEFAULT_CRATE = "rapid_types"

__all__ = ["NAME", "DEFAULT_CRATE", "UnsupportedInput", "companions", "crate_for", "embed", "generate", "needs",
           "view"]

def companions(asset: "LoadedAsset | None") -> tuple[str, ...]:
    """An asset's bridge carries the qos target's Cyclone DDS configurations."""
    return ("qos",) if asset is not None else ()


def embed(files: list[GeneratedFile], other: dict[str, list[GeneratedFile]]) -> list[GeneratedFile]:
    """The qos target's cyclonedds/<transport>.xml built into the bridge (bridge/src/transports.rs)."""
    from rapidgen.backends.rust import bridge
    target = f"{bridge.BRIDGE}/src/transports.rs"
    qos = {f.path: f.content for f in other.get("qos", [])}
    out = []
    for f in files:
        if f.path == target:
            content = f.content
            for t in bridge.TRANSPORTS:
                xml = qos.get(f"cyclonedds/{t}.xml")
                if xml is not None:
                    content = content.replace(bridge.TRANSPORT_MARK.format(t), rust_str(xml) + ";", 1)
            f = GeneratedFile(f.path, content)
        out.append(f)
    return out


def needs(asset: "LoadedAsset | None") -> frozenset[str]:
    """An asset's crate carries its QoS profiles' values (asset::QOS_PROFILES)."""
    return frozenset({QOS_LIBRARY}) if asset is not None else frozenset()


def crate_for(asset: "LoadedAsset | None", options: Options) -> str:
    if options.package:
        return crate_name(options.package)
    if asset is not None:
        return crate_name("rapid_" + (re.sub(r"[^a-z0-9]+", "_", asset.spec.name.lower()).strip("_") or "asset"))
    return DEFAULT_CRATE


def view(model: Model, asset: "LoadedAsset | None", options: Options) -> "tuple[CrateView, AssetView | None]":
    builder = Builder(model)
    c = builder.build(crate_for(asset, options), notice(options.source), options.source)
    if asset is None:
        return c, None
    from rapidgen.backends.rust.asset import build as asset_view  # an asset's tables: assets only
    from rapidgen.qos.spec import QosSpec  # the driver read the library for an asset (needs())
    library = options.qos_library if isinstance(options.qos_library, QosSpec) else None
    return c, asset_view(asset, builder, library)


def generate(model: Model, asset: "LoadedAsset | None", options: Options) -> list[GeneratedFile]:
    """Raises UnsupportedInput when the model uses what the rust target cannot express."""
    c, a = view(model, asset, options)
    files = [GeneratedFile("Cargo.toml", render("rust", "Cargo.toml.j2", c=c)),
             GeneratedFile("src/cdr.rs", support_file("rust", "cdr.rs", c.header))]
    for m in c.modules:
        template = "lib.rs.j2" if m.file == "src/lib.rs" else "module.rs.j2"
        files.append(GeneratedFile(m.file, render("rust", template, c=c, m=m, asset=a is not None)))
    if a is not None:
        files.append(GeneratedFile("src/asset.rs", render("rust", "asset.rs.j2", c=c, a=a)))
        assert asset is not None
        files += _bridge(asset, c, a)
    # the fixed glue, then this crate's types made keyed topic types (and the asset's topics)
    files.append(GeneratedFile("src/dds.rs", support_file("rust", "dds.rs", c.header)
                               + render("rust", "dds.rs.j2", c=c, asset=a is not None)))
    if c.serde_arrays:
        files.append(GeneratedFile("src/serde_arrays.rs", support_file("rust", "serde_arrays.rs", c.header)))
    check_output(files, asset)
    return sorted(files, key=lambda f: f.path)


def _bridge(asset: "LoadedAsset", c: CrateView, a: "AssetView") -> list[GeneratedFile]:
    """The bridge crate (bridge.py): generated files, and the user's handlers.rs written once."""
    from rapidgen.backends.rust import bridge, tables
    v = bridge.build(asset, c.crate, a.configs, a.stream_types)
    b = bridge.BRIDGE
    files = [GeneratedFile(f"{b}/Cargo.toml", render("rust", "bridge/Cargo.toml.j2", c=c, v=v)),
             GeneratedFile(f"{b}/src/tables.rs", render("rust", "bridge/tables.rs.j2", c=c, v=v,
                                                        tables_json=tables.json_text(asset)))]
    files += [GeneratedFile(f"{b}/src/{name}.rs", render("rust", f"bridge/{name}.rs.j2", c=c, v=v))
              for name in ("dispatch", "main", "cmd", "transports")]
    files.append(GeneratedFile(f"{b}/src/handlers.rs", render("rust", "bridge/handlers.rs.j2", c=c, v=v),
                               user_owned=True))
    return files
