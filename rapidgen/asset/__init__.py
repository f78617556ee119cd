"""Asset capability descriptors: YAML format, JSON Schema, loader, checks, computed configs.

    from rapidgen.asset import load_asset
    loaded = load_asset("specs/assets/k10.yaml", sink)   # LoadedAsset(spec, model) or None
"""
from rapidgen.asset.load import LoadedAsset, load_asset
from rapidgen.asset.spec import AssetSpec

__all__ = ["AssetSpec", "LoadedAsset", "load_asset"]
