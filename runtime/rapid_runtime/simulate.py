"""A plausible simulated robot behind the handlers (`--simulate`): a body that drives
toward a commanded point, joints that move toward setpoints, a battery that drains, and
every declared telemetry topic at its declared rate: agent, position and joint samples,
pictures (a synthetic landscape of the declared size and MIME type, with the sensor's
state), extension types filled with plausible values (a GPS fix where the body is), a
text message at start. Every command of the dictionary gets an answer: moves and joint
setpoints take the time the motion takes (and can be canceled or preempted), a picture
command on a camera's subsystem publishes its pictures, anything else completes after a
short pause."""
from __future__ import annotations

import math
import re
import threading
import time
from typing import TYPE_CHECKING

from rapid_runtime import images
from rapid_runtime import messages as M
from rapid_runtime.dds import type_class
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
# The site frame's origin on Earth (NASA Ames' Roverscape), x north and y east in metres,
# z down: where simulated GPS fixes put the body.
SITE = (37.41950, -122.06470, 10.0)  # latitude, longitude (degrees), altitude (m)
METRES_PER_DEGREE = 111_320.0
# A command on a subsystem with cameras whose name says it takes pictures publishes them.
PICTURE_COMMAND = re.compile(r"picture|image|photo|snap|capture|panorama|acquire|shoot", re.I)
PAIRED = ("agent", "position", "joint")  # published at 1 Hz when their rate is not declared
# Extension samples and states without a declared rate, and cameras without one that no
# command triggers, go out every IDLE_PERIOD seconds: a reader that joins sees them.
IDLE_PERIOD = 5.0


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
        self.frames: dict[int, int] = {}  # pictures taken per camera (image entry index)
        self.reported: set[tuple[int, str]] = set()  # telemetry failures logged (entry, message)

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
        cameras = self._cameras(ctx.subsystem, e.name, kw)
        if cameras:
            return self._take_pictures(ctx, cameras)
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

    # ---- cameras ----------------------------------------------------------------------------
    def _cameras(self, subsystem: str, command: str, kw: dict) -> list[int]:
        """Indexes (among image entries) of the cameras a picture command on `subsystem`
        uses: those a string argument names (mode=left picks PanCamLeft), else all of them."""
        if not PICTURE_COMMAND.search(command):
            return []
        own = [i for i, t in enumerate(self._of_kind("image")) if t.get("subsystem") == subsystem]
        words = [v.lower() for v in kw.values() if isinstance(v, str) and v]

        def names(i: int) -> str:
            t = self._of_kind("image")[i]
            return " ".join(str(t.get(k) or "") for k in ("sensor", "sensor_type", "suffix")).lower()
        named = [i for i in own if any(w in names(i) for w in words)]
        return named or own

    def _take_pictures(self, ctx, cameras: list[int]) -> str:
        if self.bridge is None:  # a command read before on_start
            raise CommandFailed("cameras not ready yet (simulated)")
        for i in cameras:
            if not ctx.sleep(0.05 / self.speed):
                raise Cancelled()
            self._picture(self.bridge.telemetry, self._of_kind("image")[i], i)
        sensors = ", ".join(str(self._of_kind("image")[i].get("sensor")) for i in cameras)
        return f"{len(cameras)} picture(s) taken: {sensors} (simulated)"

    def _picture_commands(self, subsystem: str | None) -> list[str]:
        return [e.name for sub, e in self.tables.entries() if sub == subsystem and PICTURE_COMMAND.search(e.name)]

    def _of_kind(self, kind: str) -> list[dict]:
        return [t for t in self.tables.telemetry if t["kind"] == kind]

    # ---- telemetry ---------------------------------------------------------------------------
    def on_start(self, bridge) -> None:
        self.bridge = bridge
        entries: list[tuple[dict, int]] = []
        seen: dict[str, int] = {}
        for t in self.tables.telemetry:
            i = seen[t["kind"]] = seen.get(t["kind"], -1) + 1
            entries.append((t, i))
        # Writers first, from the bridge's thread, before the publishing threads start
        types = {p["topic"]: p["type"] for p in self.tables.publications}
        for t, i in entries:
            for role, topic in t["topics"].items():
                name = t.get("types", {}).get(role) or types.get(topic)
                if name and topic not in self.tables.configs:
                    try:
                        bridge.node.writer(topic, type_class(bridge.rapid, name))
                    except Exception as exc:  # its samples will say so again; the bridge keeps running
                        self._report(bridge, t, i, exc)
        self._once(bridge, entries)
        fast: list[tuple[dict, int, Rate]] = []
        slow: list[tuple[dict, int, Rate]] = []
        for t, i in entries:
            rate = t.get("rate")
            if t["kind"] in PAIRED:
                fast.append((t, i, Rate(rate or 1.0)))
            elif t["kind"] == "custom" or (t["kind"] == "text" and rate):
                fast.append((t, i, Rate(rate or 1.0 / IDLE_PERIOD)))
            elif t["kind"] == "image" and (rate or not self._picture_commands(t.get("subsystem"))):
                # pictures take tens of milliseconds to paint: their own thread keeps the others' rates
                slow.append((t, i, Rate(rate or 1.0 / IDLE_PERIOD)))
        threading.Thread(target=self._publish, args=(fast, True), daemon=True, name="sim-telemetry").start()
        if slow:
            threading.Thread(target=self._publish, args=(slow, False), daemon=True, name="sim-images").start()

    def on_stop(self) -> None:
        self.stopping.set()

    def _once(self, bridge, entries) -> None:
        """At start: extension configs (durable; those the tables do not compute), each
        camera's state, a text message."""
        tel = bridge.telemetry
        for t, i in entries:
            try:
                if t["kind"] == "custom":
                    if "config" in t["topics"] and t["topics"]["config"] not in self.tables.configs:
                        self._custom(tel, t, i, "config")
                elif t["kind"] == "image":
                    tel.image_state(index=i)
                elif t["kind"] == "text":
                    tel.text(f"{self.tables.name} simulated: {len(self.tables.telemetry)} telemetry entries",
                             category=_category(t), index=i)
            except Exception as exc:  # telemetry may be dropped; the bridge keeps running
                self._report(bridge, t, i, exc)

    def _report(self, bridge, t: dict, i: int, exc: Exception) -> None:
        """Log a telemetry failure once per entry and message (not once per sample)."""
        key = (id(t), str(exc))
        if key not in self.reported:
            self.reported.add(key)
            bridge.log(f"simulated {t['kind']} telemetry {i} not sent: {type(exc).__name__}: {exc}")

    def _publish(self, entries, drain: bool) -> None:
        bridge = self.bridge
        assert bridge is not None  # started by on_start, after it is set
        tel = bridge.telemetry
        last = time.monotonic()
        # Wake for the next sample due, not every TICK: a declared 500 Hz must go out at 500 Hz.
        while not self.stopping.wait(max(0.0, min([TICK] + [r.next - time.monotonic() for _t, _i, r in entries]))):
            now = time.monotonic()
            elapsed, last = now - last, now
            if drain:
                with self.lock:
                    for k, v in self.agent.items():
                        if "battery" in k.lower() and isinstance(v, float) and ("charge" in k.lower() or "%" in k):
                            self.agent[k] = max(0.0, v - DRAIN * elapsed * self.speed)
            for t, i, rate in entries:
                if not rate.due():
                    continue
                try:
                    self._sample(tel, t, i)
                except Exception as exc:  # telemetry may be dropped; the bridge keeps running
                    self._report(bridge, t, i, exc)

    def _sample(self, tel, t: dict, i: int) -> None:
        if t["kind"] == "image":
            self._picture(tel, t, i)
            return
        if t["kind"] == "custom":
            for role in ("state", "sample"):
                if role in t["topics"]:
                    self._custom(tel, t, i, role)
            return
        if t["kind"] == "text":
            with self.lock:
                where = f"at {self.xyz[0]:.1f}, {self.xyz[1]:.1f}"
            tel.text(f"{self.tables.name} {where} (simulated)", category=_category(t), index=i)
            return
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

    def _picture(self, tel, t: dict, i: int) -> None:
        """One synthetic picture of the declared size and MIME type, seen from the body's
        heading, with the camera's state."""
        mime = t.get("mime") or "image/jpeg"
        width, height = int(t.get("width") or 640), int(t.get("height") or 480)
        with self.lock:
            heading = self.heading
            frame = self.frames[i] = self.frames.get(i, -1) + 1
        grey = any(w in str(t.get("sensor_type") or "").lower() for w in ("mono", "gray", "grey"))
        data = images.synthetic(mime, width, height, heading=heading, frame=frame, grey=grey)
        tel.image(data, mime=mime, width=width, height=height, index=i, state=True)

    def _custom(self, tel, t: dict, i: int, role: str) -> None:
        assert self.bridge is not None
        cls = type_class(self.bridge.rapid, t["types"][role])
        with self.lock:
            here = Here(list(self.xyz), self.heading, math.hypot(*self.velocity[:2]), self.tables.name)
        tel.custom(plausible(cls, here), role=role, index=i)


def _category(t: dict) -> str:
    cats = t.get("categories") or [""]
    return "system" if "system" in cats else cats[0]


# ---- plausible values for any generated type (extension telemetry) ----------------------------

class Here:
    """What the simulated body knows, for plausible values: position in the site frame (m),
    heading (rad), speed (m/s), the asset's name."""

    def __init__(self, xyz, heading: float, speed: float, asset: str) -> None:
        self.xyz, self.heading, self.speed, self.asset = xyz, heading, speed, asset

    def latitude(self) -> float:
        return SITE[0] + self.xyz[0] / METRES_PER_DEGREE

    def longitude(self) -> float:
        return SITE[1] + self.xyz[1] / (METRES_PER_DEGREE * math.cos(math.radians(SITE[0])))

    def altitude(self) -> float:
        return SITE[2] - self.xyz[2]


def words(name: str) -> list[str]:
    """latitudeDeg -> [latitude, deg]; GPS_FIX_3D -> [gps, fix, 3d]; num_sats -> [num, sats]."""
    return [w.lower() for w in re.findall(r"[A-Z]?[a-z]+|[A-Z]+(?![a-z])|\d+[A-Za-z]*", name)]


_GOOD = {"ok", "nominal", "good", "valid", "ready", "on", "enabled", "active", "locked", "normal", "3d", "running"}
_BAD = {"none", "unknown", "invalid", "error", "fail", "failed", "failure", "off", "fault", "no", "not", "disabled",
        "init", "undefined", "lost", "estop", "critical"}
# (words any of which names the member, the value): the first rule that matches
_NUMBER_RULES: list[tuple[set, object]] = [
    ({"lat", "latitude"}, Here.latitude),
    ({"lon", "lng", "long", "longitude"}, Here.longitude),
    ({"alt", "altitude", "elevation", "elev"}, Here.altitude),
    ({"dop", "hdop", "pdop", "vdop", "gdop"}, lambda h: 0.9),
    ({"sat", "sats", "satellites", "satellite", "svs"}, lambda h: 9),
    ({"heading", "yaw", "course", "bearing", "azimuth"}, lambda h: h.heading),
    ({"speed", "velocity", "vel"}, lambda h: h.speed),
    ({"temperature", "temp"}, lambda h: 21.5),
    ({"voltage", "volt", "volts"}, lambda h: 28.0),
    ({"current", "amps", "amp"}, lambda h: 1.2),
    ({"charge", "percent", "soc"}, lambda h: 80.0),
    ({"accuracy", "sigma", "std", "stddev", "uncertainty"}, lambda h: 0.5),
    ({"count", "num", "number"}, lambda h: 1),
]
_TEXT_RULES = [({"datum"}, "WGS84"), ({"frame"}, "site"), ({"name", "asset", "source", "src"}, None),
               ({"unit", "units"}, "m")]
_ROTATION = {"rot", "rotation", "orientation", "attitude", "mat", "matrix"}


def _number(name: str, s, here: Here):
    ws = set(words(name))
    value: float = 0.0
    if ws & {"time", "stamp", "timestamp"}:
        value = M.now_us() if s.kind == "int" and (s.bound or 64) >= 64 else time.time()
    else:
        for keys, rule in _NUMBER_RULES:
            if ws & keys:
                value = rule(here)  # type: ignore[operator]
                break
    if s.kind == "int":
        bits = s.bound or 64
        lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if s.signed else (0, (1 << bits) - 1)
        return max(lo, min(hi, int(round(value))))
    return float(value)


def _text(name: str, bound: int | None, here: Here) -> str:
    ws = set(words(name))
    text = "simulated"
    for keys, value in _TEXT_RULES:
        if ws & keys:
            text = here.asset if value is None else value
            break
    raw = text.encode("utf-8")[:bound] if bound is not None else text.encode("utf-8")
    return raw.decode("utf-8", "ignore")


def _enumerator(cls):
    members = list(cls)
    for e in members:
        if set(words(e.name)) & _GOOD:
            return e
    for e in members:
        if not set(words(e.name)) & _BAD:
            return e
    return members[0]


def plausible_value(tp, name: str, here: Here, depth: int = 0):
    """A plausible value of member annotation tp, named `name` (see plausible)."""
    s = M.shape(tp)
    if s.kind == "struct":
        return plausible(s.cls, here, depth + 1)
    if s.kind == "enum":
        return _enumerator(s.cls)
    if s.kind == "union":
        case, sub = next(iter(M.members(s.cls).items()))
        return s.cls(**{case: plausible_value(sub, case, here, depth + 1)})
    if s.kind == "optional":
        return plausible_value(s.elem, name, here, depth)
    if s.kind == "array":
        elem = M.shape(s.elem)
        if elem.kind == "float" and s.bound == 9 and set(words(name)) & _ROTATION:
            return list(M.IDENTITY)
        if elem.kind == "float" and s.bound == 4 and set(words(name)) & {"quat", "quaternion", "q"}:
            return [0.0, 0.0, 0.0, 1.0]
        return [plausible_value(s.elem, name, here, depth + 1) for _ in range(s.bound or 0)]
    if s.kind == "sequence":
        elem = M.shape(s.elem)
        if depth > 6 or s.bound == 0 or (elem.kind == "int" and elem.bound == 8):
            return []  # octets: no made-up payload; deep nesting: stop
        return [plausible_value(s.elem, name, here, depth + 1)]
    if s.kind == "string":
        return _text(name, s.bound, here)
    if s.kind == "char":
        return "A"
    if s.kind == "bool":
        return bool(set(words(name)) & (_GOOD | {"fix", "lock", "healthy", "available", "valid"}))
    return _number(name, s, here)


def plausible(cls, here: Here, depth: int = 0):
    """An instance of a generated struct with plausible values, chosen by member name and
    type: a position where the body is (latitude, longitude, altitude from the site frame),
    heading and speed from the body, dilution of precision 0.9, 9 satellites, 21.5 degC,
    28 V...; strings "simulated" (datum WGS84, frame site, a name the asset's), enumerators
    that say all is well (GPS_FIX_3D, ..._OK) or the first that says nothing is wrong,
    identity rotations, one element per sequence (none for octets), other numbers 0. Strings
    and sequences keep within their bounds, integers within their type. The `hdr` member is
    left for the publisher to fill."""
    values = {}
    for name, tp in M.members(cls).items():
        if name == "hdr":
            continue
        values[name] = plausible_value(tp, name, here, depth)
    return cls(**values)
