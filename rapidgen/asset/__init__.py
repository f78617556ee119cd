"""Asset capability descriptors: YAML format, JSON Schema, loader, checks, computed configs.

    from rapidgen.asset import load_asset
    loaded = load_asset("specs/assets/k10.yaml", sink)   # LoadedAsset(spec, model) or None

The names below are imported on first use (PEP 562): a back end that needs only the
descriptor's classes (rapidgen.asset.spec) does not pay for the loader's jsonschema.
"""
from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from rapidgen.asset.load import LoadedAsset, load_asset
    from rapidgen.asset.spec import AssetSpec

__all__ = ["AssetSpec", "LoadedAsset", "load_asset"]
_HOME = {"AssetSpec": "rapidgen.asset.spec", "LoadedAsset": "rapidgen.asset.load", "load_asset": "rapidgen.asset.load"}


def __getattr__(name: str) -> Any:
    if name not in _HOME:
        raise AttributeError(f"module 'rapidgen.asset' has no attribute {name!r}")
    value = getattr(importlib.import_module(_HOME[name]), name)
    globals()[name] = value
    return value
