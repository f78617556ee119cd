"""A plausible simulated robot behind the handlers (`--simulate`): a body that drives
toward a commanded point, joints that move toward setpoints, a battery that drains, and
telemetry at the declared rates. Every command of the dictionary gets an answer: moves
and joint setpoints take the time the motion takes (and can be canceled or preempted),
anything else completes after a short pause."""
from __future__ import annotations

import math
import threading
import time
from typing import TYPE_CHECKING

from rapid_runtime.handlers import Cancelled, CommandFailed, Handlers
from rapid_runtime.tables import Tables
from rapid_runtime.telemetry import Rate

if TYPE_CHECKING:  # (the bridge imports the handlers it runs)
    from rapid_runtime.bridge import Bridge

DRIVE_SPEED = 0.5  # m/s
TURN_SPEED = 0.5  # rad/s
JOINT_SPEED = 1.0  # rad/s
DRAIN = 0.02  # battery %/s
TICK = 0.05  # s


class Simulator(Handlers):
    def __init__(self, tables: Tables, speed: float = 1.0) -> None:
        self.tables = tables
        self.speed = max(speed, 1e-3)
        self.lock = threading.Lock()
        self.xyz = [0.0, 0.0, 0.0]
        self.heading = 0.0
        self.velocity = [0.0, 0.0, 0.0]
        joints = [j for t in tables.telemetry if t["kind"] == "joint" for j in t["joints"]]
        self.joint_names = [j["frame"] for j in joints]
        self.joint_limits = [(j.get("min"), j.get("max")) for j in joints]
        self.joint_pos = [self._clamp(0.0, lim) for lim in self.joint_limits]
        self.agent = {}
        for t in tables.telemetry:
            if t["kind"] == "agent":
                for v in t["values"]:
                    self.agent[v["name"]] = self._initial(v)
        self.bridge: Bridge | None = None  # set by on_start
        self.stopping = threading.Event()
        self.odometer = 0.0

    @staticmethod
    def _clamp(x: float, lim) -> float:
        lo, hi = lim
        x = max(x, lo) if lo is not None else x
        return min(x, hi) if hi is not None else x

    @staticmethod
    def _initial(v: dict):
        if v.get("has_default"):
            return v["default"]
        name = v["name"].lower()
        if v["type"] in ("RAPID_FLOAT", "RAPID_DOUBLE"):
            if "battery" in name and v.get("max") is not None:
                return float(v["max"]) if "charge" in name or v.get("unit") == "%" else (v["max"] + (v["min"] or 0)) * 0.85
            lo, hi = v.get("min"), v.get("max")
            return float(lo + hi) / 2 if lo is not None and hi is not None else 20.0
        return {"RAPID_BOOL": False, "RAPID_STRING": v["allowed"][0] if v.get("allowed") else "",
                "RAPID_INT": int(v.get("min") or 0), "RAPID_LONGLONG": 0,
                "RAPID_VEC3d": [0.0] * 3, "RAPID_MAT33f": [0.0] * 9}.get(v["type"], 0.0)

    # ---- handler dispatch: every method name in the dictionary ---------------------------------
    def __getattr__(self, method: str):
        for sub, entry in self.tables.entries():
            if entry.method == method:
                return lambda ctx, **kw: self.run(ctx, entry, kw)
        raise AttributeError(method)

    def run(self, ctx, entry, kw: dict):
        e = entry
        if (e.subsystem_type, e.name) == ("Mobility", "stopAllMotion"):
            self.velocity = [0.0, 0.0, 0.0]
            return "stopped (simulated)"
        if e.subsystem_type == "Mobility" and e.name in ("simpleMove", "move"):
            x, y, th = (list(kw.values())[1] + [0, 0, 0])[:3]
            return self._drive(ctx, x, y, th)
        if e.subsystem_type == "Mobility" and e.name == "move6DOF":
            x, y, _z = list(kw.values())[1]
            return self._drive(ctx, x, y, self.heading)
        if e.subsystem_type == "Queue" and e.name == "loadMacro":
            return f"macro {str(list(kw.values())[0])[:40]} is empty (simulated)"
        targets = self._joints_of(ctx.subsystem)
        numbers = [float(x) for v in kw.values() for x in (v if isinstance(v, list) else [v])
                   if isinstance(x, (int, float)) and not isinstance(x, bool)]
        if targets and numbers:
            return self._move_joints(ctx, targets, numbers)
        if not ctx.sleep(0.05 / self.speed):
            raise Cancelled()
        return "done (simulated)"

    def _drive(self, ctx, x: float, y: float, th: float) -> str:
        while True:
            with self.lock:
                dx, dy = x - self.xyz[0], y - self.xyz[1]
                dist = math.hypot(dx, dy)
                dth = math.remainder(th - self.heading, math.tau)
                if dist < 1e-3 and abs(dth) < 1e-3:
                    self.velocity = [0.0, 0.0, 0.0]
                    return f"arrived at {x:.2f}, {y:.2f}"
                step = min(dist, DRIVE_SPEED * TICK * self.speed)
                if dist > 0:
                    self.xyz[0] += dx / dist * step
                    self.xyz[1] += dy / dist * step
                    self.odometer += step
                turn = max(-TURN_SPEED * TICK * self.speed, min(TURN_SPEED * TICK * self.speed, dth))
                self.heading += turn
                self.velocity = [dx / dist * DRIVE_SPEED if dist else 0.0, dy / dist * DRIVE_SPEED if dist else 0.0, 0.0]
            if not ctx.sleep(TICK):
                with self.lock:
                    self.velocity = [0.0, 0.0, 0.0]
                raise Cancelled()

    def _joints_of(self, subsystem: str) -> list[int]:
        own = [i for i, f in enumerate(self.joint_names) if f.split("/")[0] == subsystem]
        if own:
            return own
        for t in self.tables.telemetry:
            if t["kind"] == "joint" and t.get("subsystem") == subsystem:
                first = self.joint_names.index(t["joints"][0]["frame"]) if t["joints"] else 0
                return list(range(first, first + len(t["joints"])))
        return []

    def _move_joints(self, ctx, targets: list[int], numbers: list[float]) -> str:
        goal = {i: self._clamp(v, self.joint_limits[i]) for i, v in zip(targets, numbers)}
        while True:
            with self.lock:
                left = 0.0
                for i, g in goal.items():
                    d = g - self.joint_pos[i]
                    step = max(-JOINT_SPEED * TICK * self.speed, min(JOINT_SPEED * TICK * self.speed, d))
                    self.joint_pos[i] += step
                    left = max(left, abs(d - step))
            if left < 1e-4:
                return f"{len(goal)} joint(s) at setpoint"
            if not ctx.sleep(TICK):
                raise Cancelled()

    # ---- telemetry ---------------------------------------------------------------------------
    def on_start(self, bridge) -> None:
        self.bridge = bridge
        threading.Thread(target=self._publish, daemon=True, name="sim-telemetry").start()

    def on_stop(self) -> None:
        self.stopping.set()

    def _publish(self) -> None:
        bridge = self.bridge
        assert bridge is not None  # started by on_start, after it is set
        tel = bridge.telemetry
        rates = [(t, Rate(t.get("rate") or 1.0)) for t in self.tables.telemetry]
        counts: dict[str, int] = {}
        last = time.monotonic()
        # Wake for the next sample due, not every TICK: a declared 500 Hz must go out at 500 Hz.
        while not self.stopping.wait(max(0.0, min([TICK] + [r.next - time.monotonic() for _t, r in rates]))):
            now = time.monotonic()
            elapsed, last = now - last, now
            with self.lock:
                for k, v in self.agent.items():
                    if "battery" in k.lower() and isinstance(v, float) and ("charge" in k.lower() or "%" in k):
                        self.agent[k] = max(0.0, v - DRAIN * elapsed * self.speed)
            counts.clear()
            for t, rate in rates:
                i = counts.get(t["kind"], 0)
                counts[t["kind"]] = i + 1
                if not rate.due():
                    continue
                try:
                    self._sample(tel, t, i)
                except Exception as exc:  # telemetry may be dropped; the bridge keeps running
                    bridge.log(f"simulated {t['kind']} telemetry not sent: {exc}")

    def _sample(self, tel, t: dict, i: int) -> None:
        with self.lock:
            if t["kind"] == "agent":
                tel.agent_state({k: v for k, v in self.agent.items() if k in {x["name"] for x in t["values"]}}, i)
            elif t["kind"] == "position":
                half = self.heading / 2
                rot = [0.0, 0.0, math.sin(half), math.cos(half)] if t.get("pose_encoding") == "RAPID_ROT_QUAT" \
                    else [0.0, 0.0, self.heading]
                values = {}
                for v in t["values"]:
                    if v["name"] == "speed":
                        values["speed"] = math.hypot(*self.velocity[:2])
                    elif v["name"] == "odometer":
                        values["odometer"] = self.odometer
                tel.position(list(self.xyz), rot, list(self.velocity), None, values, i)
            elif t["kind"] == "joint":
                names = [j["frame"] for j in t["joints"]]
                tel.joints([self.joint_pos[self.joint_names.index(n)] for n in names], index=i)
