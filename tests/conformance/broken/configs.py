"""Broken assets: configs (conformance/configs.py)."""
from __future__ import annotations

from . import kind


@kind("position-config-unpublished", "CFG-01")
def position_config_unpublished(a):
    """The PositionConfig is never written (waiting for a localizer frame that never
    comes); its samples still go out. CFG-02..05, TEL-02/03/07, DDS-03/07 are BLOCKED."""
    topic = a.entry("position")["topics"]["config"]
    publish = a.bridge.publish_config

    def skip(t, value=None):
        if t != topic:
            return publish(t, value)
        return a.bridge.serials.update(t, a.tables.configs[t][1] if value is None else value)[0]
    a.bridge.publish_config = skip


@kind("volatile-config", "CFG-02")
def volatile_config(a):
    from cyclonedds.qos import Policy, Qos
    a.patch_qos({t: Qos(Policy.Durability.Volatile) for t in a.tables.configs})


@kind("wrong-config", "CFG-03")
def wrong_config(a):
    """The CommandConfig lists one subsystem fewer than the descriptor implies."""
    type_name, value = a.tables.configs["rapid_command_config"]
    a.tables.configs["rapid_command_config"] = (type_name,
                                                dict(value, availableSubsystems=value["availableSubsystems"][:-1]))


@kind("config-without-source", "CFG-04")
def config_without_source(a):
    """Configs built before the bridge knew its name: srcName left empty (samples are fine)."""
    config = a.M.config

    def unnamed(rapid, type_name, value, hdr):
        hdr.srcName = ""
        return config(rapid, type_name, value, hdr)
    a.M.config = unnamed


@kind("zero-serial", "CFG-05")
def zero_serial(a):
    a.bridge.serials.start = 0
    a.bridge.serials._last = 0


@kind("serial-drift", "CFG-05")
def serial_drift(a):
    """The CommandConfig republished every 3 s with a new serial and the same content (a
    bridge that stamps each publication anew), so only the rule that a serial stays put
    while the content does is broken. Caught only by a judgment at the end of the run: the
    first publications look right. (Only a config no sample follows: drifting the telemetry
    configs too raced TEL-02 under load, a sample stamped before a republish read after it.)"""
    import threading

    from rapid_runtime.dds import type_class

    b = a.bridge

    def republish():
        while not b.stopped.wait(3.0):
            for topic, (type_name, value) in a.tables.configs.items():
                if topic != "rapid_command_config":
                    continue
                serial = b.serials._last = b.serials._last + 1
                b.serials._serial[topic] = serial
                hdr = a.M.header(a.rapid, b.name, b.name, serial)
                b.node.writer(topic, type_class(a.rapid, type_name)).write(a.M.config(a.rapid, type_name, value, hdr))
    threading.Thread(target=republish, daemon=True, name="serial-drift").start()


@kind("config-order", None)
def config_order(a):
    """The CommandConfig's subsystems, subsystem types and each type's commands in the
    reverse of the descriptor's order (Astrobee keeps its config file's order, soraCore
    sorts by name: rapid-protocol.md 5b): must pass, the order reported as information."""
    type_name, value = a.tables.configs["rapid_command_config"]
    types = [dict(t, commands=list(reversed(t["commands"]))) for t in reversed(value["availableSubsystemTypes"])]
    a.tables.configs["rapid_command_config"] = (type_name, dict(
        value, availableSubsystems=list(reversed(value["availableSubsystems"])), availableSubsystemTypes=types))
