"""A seed asset's generated tables, read as the runtime reads them (no DDS)."""
from __future__ import annotations

import importlib.util

from tests.runtime.live import SEEDS, python_dir


def tables(asset: str):
    from rapid_runtime.tables import Tables
    path = python_dir(asset) / SEEDS[asset] / "asset_tables.py"
    spec = importlib.util.spec_from_file_location(f"tables_{SEEDS[asset]}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return Tables(module)


def entries(asset: str) -> list:
    return list(tables(asset).entries())
