"""Broken assets: telemetry (conformance/telemetry.py). Patches go on the runtime's
TelemetryPublisher class: this process runs one bridge only."""
from __future__ import annotations

import time

from . import kind


@kind("position-silent", "TEL-01")
def position_silent(a):
    """The position writer exists but nothing is written (no localizer fix, no heartbeat).
    TEL-02..07 are then BLOCKED."""
    a.writer(a.entry("position")["topics"]["sample"])
    a.B.TelemetryPublisher.position = lambda self, *args, **kw: None


@kind("wrong-serial", "TEL-02")
def wrong_serial(a):
    hdr = a.B.TelemetryPublisher._hdr

    def off_by_one(self, entry, stamp=None):
        h = hdr(self, entry, stamp)
        h.serial += 1
        return h
    a.B.TelemetryPublisher._hdr = off_by_one


@kind("misaligned-values", "TEL-03")
def misaligned_values(a):
    values = a.B.TelemetryPublisher._values
    a.B.TelemetryPublisher._values = lambda self, entry, v: list(reversed(values(self, entry, v))) + \
        [a.M.union(a.rapid, "RAPID_BOOL", True)]


@kind("millisecond-stamps", "TEL-04")
def millisecond_stamps(a):
    hdr = a.B.TelemetryPublisher._hdr
    a.B.TelemetryPublisher._hdr = lambda self, entry, stamp=None: hdr(self, entry, time.time_ns() // 1_000_000)


@kind("sample-without-source", "TEL-05")
def sample_without_source(a):
    """Telemetry headers with an empty srcName (configs carry theirs)."""
    hdr = a.B.TelemetryPublisher._hdr

    def unnamed(self, entry, stamp=None):
        h = hdr(self, entry, stamp)
        h.srcName = ""
        return h
    a.B.TelemetryPublisher._hdr = unnamed


@kind("slow-rate", "TEL-06")
def slow_rate(a):
    a.tables.telemetry = [dict(t, rate=t["rate"] / 2) if t.get("rate") else t for t in a.tables.telemetry]
    a.bridge.telemetry.entries = a.tables.telemetry


@kind("millivolts", "TEL-07")
def millivolts(a):
    """batteryVoltage sent in millivolts (declared V, range 0-60)."""
    values = a.B.TelemetryPublisher._values

    def scaled(self, entry, v):
        if v and isinstance(v.get("batteryVoltage"), float):
            v = dict(v, batteryVoltage=v["batteryVoltage"] * 1000)
        return values(self, entry, v)
    a.B.TelemetryPublisher._values = scaled


@kind("gps-silent", "TEL-08")
def gps_silent(a):
    """The GPS extension's writer exists but no fix is ever written (the plugin is not loaded)."""
    a.quiet.add(a.entry("custom")["topics"]["sample"])


@kind("frozen-stamps", "TEL-04")
def frozen_stamps(a):
    """Every sample stamped with the bridge's start time (microseconds, recent at first):
    the stamps never advance. TEL-06 (rates from the stamps) is then BLOCKED."""
    start = time.time_ns() // 1000
    hdr = a.B.TelemetryPublisher._hdr
    a.B.TelemetryPublisher._hdr = lambda self, entry, stamp=None: hdr(self, entry, start)
