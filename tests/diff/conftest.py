"""Helpers for the diff tests: OLD/NEW pairs written to a folder and compared."""
from __future__ import annotations

import copy
import os

import yaml

from rapidgen.diagnostics import DiagnosticSink
from rapidgen.diff.command import compare
from rapidgen.diff.sides import load_side

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RAPID = os.path.join(REPO, "specs", "rapid")

# A small robot touching every protocol rule: one custom command set, agent and position
# values, a joint group, an image topic with a QoS override.
BASE = {
    "version": 1,
    "asset": {"name": "Probe", "kind": "rover"},
    "dds": {"domain": 0},
    "idl": {"rapid": RAPID},
    "subsystem_types": [{
        "name": "Arm", "description": "an arm",
        "commands": [
            {"name": "move", "abortable": True, "suspendable": True, "parameters": [
                {"name": "x", "type": "RAPID_FLOAT", "unit": "m", "range": [-1, 1]},
                {"name": "y", "type": "RAPID_FLOAT", "unit": "m", "range": [-1, 1]},
                {"name": "mode", "type": "RAPID_STRING", "allowed": ["slow", "fast"]}]},
            {"name": "stow", "parameters": []}]}],
    "subsystems": [{"name": "Admin"}, {"name": "Mobility"}, {"name": "RightArm", "type": "Arm"}],
    "telemetry": [
        {"kind": "position", "rate": 1, "frame": "site", "values": [
            {"key": "speed", "type": "RAPID_FLOAT", "unit": "m/s"},
            {"key": "odometer", "type": "RAPID_DOUBLE", "unit": "m"}]},
        {"kind": "agent", "rate": 1, "values": [
            {"key": "battery", "type": "RAPID_FLOAT", "unit": "%"},
            {"key": "mode", "type": "RAPID_STRING"}]},
        {"kind": "joint", "group": "arm", "rate": 10, "joints": [
            {"frame": "Arm/J0", "dof": "pitch", "unit": "rad"},
            {"frame": "Arm/J1", "dof": "yaw", "unit": "rad"}]},
        {"kind": "image", "suffix": "cam", "sensor": "Cam", "qos": {"sample": "RapidReliableQos"}},
    ],
}


def base() -> dict:
    return copy.deepcopy(BASE)


def write(folder, name: str, text: str) -> str:
    path = os.path.join(str(folder), name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def idl_pair(tmp_path, old: str, new: str) -> tuple[str, str]:
    return (write(tmp_path / "old", "t.idl", f"module t {{\n{old}\n}};\n"),
            write(tmp_path / "new", "t.idl", f"module t {{\n{new}\n}};\n"))


def asset_pair(tmp_path, old: dict, new: dict) -> tuple[str, str]:
    return (write(tmp_path / "old", "probe.yaml", yaml.safe_dump(old, sort_keys=False)),
            write(tmp_path / "new", "probe.yaml", yaml.safe_dump(new, sort_keys=False)))


def diff_paths(old_path: str, new_path: str):
    sink = DiagnosticSink()
    old = load_side(old_path, [], {}, sink)
    new = load_side(new_path, [], {}, sink)
    assert old is not None and new is not None, [str(d) for d in sink.diagnostics]
    return compare(old, new)
