"""The ROS 2 bridge's handlers: every command of the asset acts on ROS 2 and its telemetry
is fed from ROS 2 subscriptions, as the package's ros2_map.py (the descriptor's ros2:
section, as data) says. A generated `<package>/ros2.py` calls main() with its tables.

- a mapped command publishes one message built from its arguments, then completes, or
  with `until` waits for a message whose field has the given value (COMPLETED/OK), the
  timeout (EXEC_FAILED) or a cancellation (CANCELED, after publishing its `cancel`
  message if it has one); or it calls a service, whose response's `success` decides
  COMPLETED/OK or EXEC_FAILED (its `message` the ack's); or it sends an action goal, whose
  feedback becomes EXECUTING acks and whose result COMPLETED (OK, EXEC_FAILED when aborted or
  rejected, CANCELED after a cancel it asked for); an unmapped one is EXEC_FAILED;
- each mapped input stream (the descriptor's streams:) is read with Cyclone on its topic in
  the writer's partition (best effort, keep last 1, DEADLINE the stream's deadline) and every
  sample is published as the mapped ROS 2 message (streams.py); a missed deadline (or the
  writer leaving) runs the stream's on_loss (stop: publish the stop message; hold, none:
  nothing), logs it and says it on the text telemetry, as the next sample's recovery does;
- a fed telemetry entry is published at its declared rate from the latest ROS 2 data (on
  each message when it has no rate), stamped with the time that data was received from
  ROS 2, not when it is republished; nothing goes out before the first message arrives (but
  a camera's ImageSensorState, and one TextMessage per text entry saying which ROS 2 node
  serves the asset, at start). Once the data is older than the entry's stale bound the
  runtime stops its samples and says the source is silent (docs/ros2.md, "When the ROS 2
  side dies").

rclpy (an RMW and the message packages beside it) is imported when the handlers are made,
never at import: ROS 2 traffic follows ROS_DOMAIN_ID and the RMW's own settings.
"""
from __future__ import annotations

import sys
import threading
import time
from types import ModuleType
from typing import Any, Callable

from rapid_runtime.bridge import main as bridge_main
from rapid_runtime.handlers import Cancelled, CommandFailed, Handlers
from rapid_runtime.ros2.fields import describe, field_value, get_field, message_class, set_field
from rapid_runtime.ros2.rotations import quat_from_m33, rapid_rot, rotate, yaw_from_quat
from rapid_runtime.ros2.streams import StreamReader

SERVICE_WAIT = 5.0  # s a service call or goal waits for its server when the mapping gives no timeout
# s a command's message waits for a subscriber to match its publisher: ROS 2 topics are
# volatile, so a goal published before the robot's node matched is lost without a word
SUBSCRIBER_WAIT = 5.0
GOAL_SUCCEEDED, GOAL_CANCELED, GOAL_ABORTED = 4, 5, 6  # action_msgs/GoalStatus


def handler_methods(asset_tables: ModuleType) -> frozenset[str]:
    """The handler method names of the asset's command dictionary."""
    return frozenset(c["method"] for commands in asset_tables.COMMANDS.values() for c in commands.values())


class Waiter:
    """One command waiting for a message whose field equals a value."""

    def __init__(self, field, equals):
        self.field, self.equals = field, equals
        self.done = threading.Event()


class Ros2Handlers(Handlers):
    """Every command's handler method (the runtime looks them up by name) acts on ROS 2:
    `ros2_map` is the package's ros2_map module, `methods` the dictionary's method names."""

    def __init__(self, ros2_map: Any, methods: frozenset[str]) -> None:
        self.map, self.methods = ros2_map, methods
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.qos import qos_profile_sensor_data

        self._rclpy = rclpy
        self.context = rclpy.context.Context()
        rclpy.init(context=self.context)
        self.node = rclpy.create_node(self.map.NODE, context=self.context)
        self.bridge: Any = None  # the rapid_runtime Bridge, from on_start
        self.lock = threading.Lock()
        self.stopping = threading.Event()
        self._logged: set[object] = set()  # telemetry entries whose failure was logged (once each)
        self.latest: dict[tuple[str, int], Any] = {}  # (kind, index) -> what the telemetry call takes
        self.received: dict[tuple[str, int], int] = {}  # (kind, index) -> when its latest data came from ROS 2 [us since the epoch]
        self.publishers: dict[tuple[str, str], Any] = {}
        self.clients: dict[tuple[str, str], Any] = {}
        for spec in self.map.COMMANDS.values():
            for pub in (spec.get("publish"), spec.get("cancel")):
                if pub is not None and (pub["topic"], pub["type"]) not in self.publishers:
                    self.publishers[(pub["topic"], pub["type"])] = self.node.create_publisher(
                        message_class(pub["type"]), pub["topic"], 10)
            call = spec.get("call")
            if call is not None and (call["service"], call["type"]) not in self.clients:
                self.clients[(call["service"], call["type"])] = self.node.create_client(
                    message_class(call["type"]), call["service"])
            act = spec.get("action")
            if act is not None and (act["action"], act["type"]) not in self.clients:
                from rclpy.action import ActionClient
                self.clients[(act["action"], act["type"])] = ActionClient(
                    self.node, message_class(act["type"]), act["action"])
        for spec in self.map.STREAMS:
            for pub in (spec["ros2"], spec["stop"]):
                if pub is not None and (pub["topic"], pub["type"]) not in self.publishers:
                    self.publishers[(pub["topic"], pub["type"])] = self.node.create_publisher(
                        message_class(pub["type"]), pub["topic"], 10)
        self.streams: list[StreamReader] = []
        self.waiters: dict[tuple[str, str], list[Waiter]] = {}  # (topic, type) -> [Waiter]
        for spec in self.map.COMMANDS.values():
            until = spec.get("until")
            if until is not None and (until["topic"], until["type"]) not in self.waiters:
                key = (until["topic"], until["type"])
                self.waiters[key] = []
                self.node.create_subscription(message_class(until["type"]), until["topic"],
                                              lambda msg, key=key: self._on_until(key, msg), 10)
        for feed in self.map.TELEMETRY:
            # best effort matches reliable and best-effort publishers alike (sensor streams are often the latter)
            self.node.create_subscription(message_class(feed["type"]), feed["topic"],
                                          lambda msg, feed=feed: self._on_feed(feed, msg), qos_profile_sensor_data)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.spinner = threading.Thread(target=self._spin, name="ros2-spin", daemon=True)
        self.spinner.start()

    def _spin(self):
        try:
            self.executor.spin()
        except Exception as exc:  # the context shut down under it: the bridge is stopping
            if not self.stopping.is_set():
                print(f"ros2: executor stopped: {exc!r}", file=sys.stderr, flush=True)

    # -- lifecycle -----------------------------------------------------------------------
    def on_start(self, bridge):
        self.bridge = bridge
        for feed in self.map.TELEMETRY:  # a camera's state (its declared metadata) goes out at once
            if feed["feeds"] == "image":
                bridge.telemetry.image_state(index=feed["index"])
        texts = [t for t in bridge.tables.telemetry if t["kind"] == "text"]
        for index, entry in enumerate(texts):  # say where the asset comes from (TextMessage is durable)
            categories = entry.get("categories") or []
            bridge.telemetry.text(f"{bridge.name} served from ROS 2 node {self.map.NODE}", index=index,
                                  category="system" if "system" in categories else (categories or [""])[0])
        threading.Thread(target=self._publish_at_rates, name="ros2-telemetry", daemon=True).start()
        self.streams = [StreamReader(self, spec, bridge).start() for spec in self.map.STREAMS]

    def on_stop(self):
        self.stopping.set()
        for stream in self.streams:
            stream.stop()
        self.executor.shutdown(timeout_sec=1.0)
        self.node.destroy_node()
        self._rclpy.try_shutdown(context=self.context)

    # -- telemetry: ROS 2 -> RAPID -------------------------------------------------------
    def _on_feed(self, feed, msg):
        key = (feed["feeds"], feed["index"])
        try:
            with self.lock:
                self.latest[key] = getattr(self, "_read_" + feed["feeds"])(feed, msg, self.latest.get(key))
                self.received[key] = time.time_ns() // 1000
            if feed["rate"] is None:
                self._publish(key)
        except Exception as exc:  # a malformed message must not stop the subscription
            self._log_once(key, f"ros2: {feed['topic']} -> {feed['feeds']} telemetry: {exc!r}")

    def _read_joint(self, feed, msg, old):
        n = len(feed["joints"])
        pos, vel, eff = old if old is not None else ([0.0] * n, [0.0] * n, [0.0] * n)
        pos, vel, eff = list(pos), list(vel), list(eff)
        where = {name: i for i, name in enumerate(msg.name)}
        for j, name in enumerate(feed["joints"]):
            i = where.get(name)
            if i is None:
                continue  # not in this message: keep the last value (JointState may be split)
            for dst, src in ((pos, msg.position), (vel, msg.velocity), (eff, msg.effort)):
                if i < len(src):
                    dst[j] = float(src[i])
        return pos, vel, eff

    def _read_position(self, feed, msg, old):
        pose = get_field(msg, feed["pose"])
        p = pose.position
        xyz, rot = [p.x, p.y, p.z], rapid_rot(pose.orientation, feed["encoding"])
        vxyz, vrot = [0.0, 0.0, 0.0], [0.0] * 9
        if feed["twist"]:  # Odometry: its twist is in child_frame_id (the body); RAPID's in the pose's frame
            twist = get_field(msg, feed["twist"])
            o = pose.orientation
            q = (o.x, o.y, o.z, o.w) if any((o.x, o.y, o.z, o.w)) else (0.0, 0.0, 0.0, 1.0)  # none filled in
            vxyz = rotate(q, [twist.linear.x, twist.linear.y, twist.linear.z])
            if feed["velocity_encoding"] == "RAPID_ROT_VEL":
                vrot = rotate(q, [twist.angular.x, twist.angular.y, twist.angular.z]) + [0.0] * 6
        return xyz, rot, vxyz, vrot

    def _read_image(self, feed, msg, old):
        """The picture's bytes: a CompressedImage's as they are, a raw Image's as PNM."""
        if not hasattr(msg, "encoding"):
            return bytes(msg.data)
        channels = {"rgb8": 3, "bgr8": 3, "mono8": 1}.get(msg.encoding)
        if channels is None:
            raise ValueError(f"encoding {msg.encoding!r}: only rgb8, bgr8 and mono8 are passed on (as PNM)")
        data, row = bytes(msg.data), msg.width * channels
        pixels = b"".join(data[y * msg.step:y * msg.step + row] for y in range(msg.height))
        if msg.encoding == "bgr8":
            swapped = bytearray(pixels)
            swapped[0::3], swapped[2::3] = pixels[2::3], pixels[0::3]
            pixels = bytes(swapped)
        return b"P%d\n%d %d\n255\n" % (6 if channels == 3 else 5, msg.width, msg.height) + pixels

    def _read_agent(self, feed, msg, old):
        values = dict(old or {})
        for key, path, conv, *scaled in feed["values"]:
            scale = scaled[0] if scaled else 1
            v = get_field(msg, path)
            if conv == "yaw":
                values[key] = yaw_from_quat(v.x, v.y, v.z, v.w) * scale
            elif conv == "vec3":
                values[key] = [v.x * scale, v.y * scale, v.z * scale]
            elif conv == "float":
                values[key] = float(v) * scale
            else:
                values[key] = {"int": int, "bool": bool, "str": str}[conv](v)
        return values

    def _publish(self, key):
        kind, index = key
        with self.lock:
            data, stamp = self.latest.get(key), self.received.get(key)
        if data is None or self.bridge is None:
            return
        t = self.bridge.telemetry
        # stamped with its source's time: past the entry's stale bound the runtime refuses it
        try:
            if kind == "joint":
                fields = t.of("joint", index).get("fields") or ["anglePos"]
                pos, vel, eff = data
                t.joints(pos, velocities=vel if "angleVel" in fields else None,
                         torques=eff if "torque" in fields else None, index=index, stamp=stamp)
            elif kind == "position":
                xyz, rot, vxyz, vrot = data
                t.position(xyz, rot, velocity_xyz=vxyz, velocity_rot=vrot, index=index, stamp=stamp)
            elif kind == "image":
                t.image(data, index=index, stamp=stamp)
            else:
                t.agent_state(data, index=index, stamp=stamp)
        except Exception as exc:  # a value the declared type refuses: say so once, go on
            self._log_once(key, f"ros2: {kind} telemetry {index}: {exc!r}")

    def _publish_at_rates(self):
        """Each fed entry with a rate, at that rate, from the latest data (sample and hold)."""
        periods: dict[tuple[str, int], float] = {}
        for feed in self.map.TELEMETRY:
            if feed["rate"]:
                periods[(feed["feeds"], feed["index"])] = 1.0 / feed["rate"]
        due = {key: time.monotonic() for key in periods}
        while periods and not self.stopping.is_set():
            key = min(due, key=lambda k: due[k])
            wait = due[key] - time.monotonic()
            if wait > 0 and self.stopping.wait(wait):
                break
            self._publish(key)
            due[key] = max(due[key] + periods[key], time.monotonic())

    # -- streams: RAPID input stream -> ROS 2 -------------------------------------------------
    def publish_stream_sample(self, spec, sample):
        """One stream sample as the mapped ROS 2 message (the writer's stamp)."""
        r = spec["ros2"]
        msg = message_class(r["type"])()
        if spec["type"] == "rapid::PositionSample":
            pose = get_field(msg, r["pose"])
            pose.position.x, pose.position.y, pose.position.z = (float(v) for v in sample.pose.xyz)
            rot = [float(v) for v in sample.pose.rot]
            q = quat_from_m33(rot) if r["encoding"] == "RAPID_ROT_M33" else rot[:4]
            pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w = (float(v) for v in q)
            if r["pose"]:
                msg.header.frame_id = r["frame"]
        else:
            msg.name = list(r["joints"])
            msg.position = [float(v) for v in sample.anglePos]
            msg.velocity = [float(v) for v in sample.angleVel]
            msg.effort = [float(v) for v in sample.torque]
        if r["stamp"]:
            micros = int(sample.hdr.timeStamp)
            if micros > 0:
                msg.header.stamp.sec, msg.header.stamp.nanosec = micros // 1_000_000, (micros % 1_000_000) * 1000
            else:
                msg.header.stamp = self.node.get_clock().now().to_msg()
        self.publishers[(r["topic"], r["type"])].publish(msg)

    def stream_state(self, spec, state, missed, text, level):
        """A stream's state change: the on_loss action, the log, the text telemetry, the agent keys."""
        if state == "lost" and spec["on_loss"] == "stop" and spec["stop"] is not None:
            self._publish_of(spec["stop"], [], wait=0.0)  # (a lost stream's stop goes out at once)
        self.bridge.log(text)
        texts = [t for t in self.bridge.tables.telemetry if t["kind"] == "text"]
        if texts:
            categories = texts[0].get("categories") or []
            self.bridge.telemetry.text(text, level=level, category="system" if "system" in categories
                                       else (categories or [""])[0])
        keys = {k: v for k, v in ((spec["state_key"], state), (spec["missed_key"], missed)) if k}
        if keys and any(t["kind"] == "agent" for t in self.bridge.tables.telemetry):
            with self.lock:
                self.latest[("agent", 0)] = {**(self.latest.get(("agent", 0)) or {}), **keys}

    def _log_once(self, key, text):
        if key not in self._logged:
            self._logged.add(key)
            if self.bridge is not None:
                self.bridge.log(text)
            else:
                print(text, file=sys.stderr, flush=True)

    # -- commands: RAPID -> ROS 2 --------------------------------------------------------
    def _on_until(self, key, msg):
        with self.lock:
            waiting = list(self.waiters[key])
        for w in waiting:
            try:
                if get_field(msg, w.field) == w.equals:
                    w.done.set()
            except Exception:  # the field is there (checked at generate time); a value mismatch is no match
                pass

    def __getattr__(self, method: str) -> Callable[..., str]:
        # only the command dictionary's methods, nothing else the runtime probes (nor an unset self.methods)
        if method not in self.__dict__.get("methods", ()):
            raise AttributeError(method)
        return self._run

    def _build(self, msg, type_name, fields, args):
        """msg with each mapped field filled from the arguments (or its constant)."""
        for path, conv, source in fields:
            try:
                set_field(msg, path, field_value(conv, source, args, get_field(msg, path)))
            except (AttributeError, IndexError, TypeError, ValueError, AssertionError) as exc:
                raise CommandFailed(f"{type_name}.{path}: {exc}") from None
        return msg

    def _publish_of(self, pub, args, wait: float = SUBSCRIBER_WAIT) -> bool:
        """Publish a command's message, once a subscriber matched or `wait` passed; False when
        none had (published all the same: the caller says so)."""
        msg = self._build(message_class(pub["type"])(), pub["type"], pub["fields"], args)
        publisher = self.publishers[(pub["topic"], pub["type"])]
        end = time.monotonic() + wait
        while publisher.get_subscription_count() == 0 and time.monotonic() < end:
            time.sleep(0.02)
        if pub["stamp"]:
            msg.header.stamp = self.node.get_clock().now().to_msg()
        publisher.publish(msg)
        return publisher.get_subscription_count() > 0

    def _run(self, ctx, **kwargs):
        key = f"{ctx.subsystem}/{ctx.entry.name}"
        spec = self.map.COMMANDS.get(key)
        if spec is None and ctx.entry.subsystem_type == "Mobility" and ctx.entry.name == "stopAllMotion":
            return "Mobility commands cancelled (no ROS 2 mapping for a stop)"  # the runtime cancelled them
        if spec is None:
            raise CommandFailed(f"{key} has no ROS 2 mapping (ros2.commands in the descriptor)")
        args = [kwargs[p.arg] for p in ctx.entry.params]
        try:
            if "call" in spec:
                return self._call(ctx, spec["call"], args)
            if "action" in spec:
                return self._act(ctx, spec["action"], args)
            return self._publish_and_wait(ctx, spec, args)
        except Cancelled:
            if spec.get("cancel") is not None:  # tell the robot to stop what the command started
                self._publish_of(spec["cancel"], args)
            raise

    def _call(self, ctx, call, args):
        """A service call; its response's success decides OK or EXEC_FAILED."""
        client = self.clients[(call["service"], call["type"])]
        end = None if call["timeout"] is None else time.monotonic() + call["timeout"]
        ready_by = time.monotonic() + (call["timeout"] or SERVICE_WAIT)
        while not client.service_is_ready():
            if not ctx.sleep(0.05):
                raise Cancelled()
            if time.monotonic() > ready_by:
                raise CommandFailed(f"service {call['service']} not available")
        request = self._build(message_class(call["type"]).Request(), call["type"], call["fields"], args)
        future = client.call_async(request)
        while not future.done():
            if not ctx.sleep(0.05):
                future.cancel()
                raise Cancelled()
            if end is not None and time.monotonic() > end:
                future.cancel()
                raise CommandFailed(f"no answer from {call['service']} within {call['timeout']:g} s")
        response = future.result()
        text = response.message if call["message"] else ""
        if call["success"] and not response.success:
            raise CommandFailed(f"{call['service']}: {text or 'success false'}")
        return text or f"{call['service']} answered"

    def _act(self, ctx, act, args):
        """An action goal: accepted -> feedback as EXECUTING acks -> the result's status.
        A cancelled command asks the server to cancel the goal and answers CANCELED."""
        client = self.clients[(act["action"], act["type"])]
        end = None if act["timeout"] is None else time.monotonic() + act["timeout"]
        ready_by = time.monotonic() + (act["timeout"] or SERVICE_WAIT)
        while not client.server_is_ready():
            if not ctx.sleep(0.05):
                raise Cancelled()
            if time.monotonic() > ready_by:
                raise CommandFailed(f"action server {act['action']} not available")
        goal = self._build(message_class(act["type"]).Goal(), act["type"], act["fields"], args)
        live, gate = [True], threading.Lock()  # no EXECUTING ack may follow the command's COMPLETED

        def on_feedback(fb):
            with gate:
                if live[0]:
                    ctx.progress(describe(fb.feedback))
        try:
            return self._goal(ctx, act, client.send_goal_async(goal, feedback_callback=on_feedback), end)
        finally:
            with gate:
                live[0] = False

    def _goal(self, ctx, act, sent, end):
        while not sent.done():
            if end is not None and time.monotonic() > end:
                raise CommandFailed(f"{act['action']}: no answer to the goal within {act['timeout']:g} s")
            time.sleep(0.02)
        handle = sent.result()
        if not handle.accepted:
            raise CommandFailed(f"{act['action']}: goal rejected")
        result = handle.get_result_async()
        cancel_asked = None
        while not result.done():
            if ctx.cancelled.is_set() and cancel_asked is None:
                handle.cancel_goal_async()
                cancel_asked = time.monotonic()
            if cancel_asked is not None and time.monotonic() > cancel_asked + SERVICE_WAIT:
                raise Cancelled()  # the server did not answer the cancel: the command is cancelled anyway
            if cancel_asked is None and end is not None and time.monotonic() > end:
                handle.cancel_goal_async()
                raise CommandFailed(f"{act['action']}: no result within {act['timeout']:g} s (goal cancelled)")
            time.sleep(0.02)
        status = result.result().status
        if status == GOAL_SUCCEEDED:
            return f"{act['action']} succeeded: {describe(result.result().result)}"
        if status == GOAL_CANCELED:
            raise Cancelled()
        raise CommandFailed(f"{act['action']}: goal {'aborted' if status == GOAL_ABORTED else f'status {status}'}")

    def _publish_and_wait(self, ctx, spec, args):
        pub = spec["publish"]
        until = spec.get("until")
        waiter = None
        if until is not None:
            waiter = Waiter(until["field"], until["equals"])
            with self.lock:
                self.waiters[(until["topic"], until["type"])].append(waiter)
        try:
            heard = self._publish_of(pub, args)
            if waiter is None:
                return f"published on {pub['topic']}" + ("" if heard else f"; no subscriber had matched within "
                                                         f"{SUBSCRIBER_WAIT:.0f} s")
            ctx.progress(f"published on {pub['topic']}; waiting for {until['field']} on {until['topic']}")
            end = None if until["timeout"] is None else time.monotonic() + until["timeout"]
            while not waiter.done.wait(0.05):
                if ctx.cancelled.is_set():
                    raise Cancelled()
                if end is not None and time.monotonic() > end:
                    raise CommandFailed(f"no {until['field']} == {until['equals']!r} on {until['topic']} "
                                        f"within {until['timeout']:g} s")
            return f"{until['topic']}: {until['field']} == {until['equals']!r}"
        finally:
            if waiter is not None:
                with self.lock:
                    self.waiters[(until["topic"], until["type"])].remove(waiter)



def make_handlers(package: str, ros2_map: Any, methods: frozenset[str]) -> Ros2Handlers:
    """Ros2Handlers, or one line saying which ROS 2 package is missing (no traceback): rclpy, an
    RMW and the message packages the mapping names come from the PyPI ROS wheels."""
    try:
        return Ros2Handlers(ros2_map, methods)
    except ModuleNotFoundError as exc:
        name = (exc.name or "").split(".")[0]
        if not name:
            raise
        wheel = "ros-" + name.replace("_", "-")
        extra = " ros-rmw-fastrtps-cpp" if name.startswith("rcl") else ""
        print(f"python -m {package}.ros2: cannot import {name} (ROS 2 Python): install {wheel}{extra} "
              "(pip, the PyPI ROS wheels; docs/ros2.md) or source a ROS 2 install", file=sys.stderr, flush=True)
        sys.exit(2)


def main(asset_tables: ModuleType, rapid: ModuleType, ros2_map: Any, package: str,
         argv: list[str] | None = None) -> int:
    """`python -m <package>.ros2`: the rapid_runtime bridge with these handlers (no --simulate)."""
    methods = handler_methods(asset_tables)
    description = ("RAPID asset " + asset_tables.ASSET["name"] + " served from the ROS 2 node " + ros2_map.NODE +
                   " (ros2_map.py). RAPID traffic follows --domain and --transport; ROS 2 traffic ROS_DOMAIN_ID "
                   "and the RMW's own settings.")
    return bridge_main(asset_tables, rapid, lambda: make_handlers(package, ros2_map, methods), package=package,
                       argv=argv, module="ros2", description=description, simulate=False)
