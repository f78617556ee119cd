"""The monitor's state and checks without a network or a browser: threshold levels, the
command dictionary merged with the descriptor's hints, a page's command request checked
(source, dictionary, types, ranges, defaults), deltas by cursor, bounded streams."""
from __future__ import annotations

from types import SimpleNamespace as NS

import pytest

from rapidgen.monitor.commanding import Refused, check
from rapidgen.monitor.hints import AssetHints, Hints, config_difference, level_of
from rapidgen.monitor.state import LOG_LINES, MAX_ASSETS, MAX_ROWS, Hub

pytest.importorskip("rapid_runtime")  # values are checked by the runtime's rules, as `rapidgen cmd` does

BATTERY = {"unit": "%", "warning": {"below": 30, "above": None}, "critical": {"below": 15, "above": None}}
VOLTAGE = {"warning": {"below": 44, "above": 56}, "critical": {"below": 40, "above": 58}}


@pytest.mark.parametrize("value,hint,level", [
    (50, BATTERY, "ok"), (30, BATTERY, "ok"), (29.9, BATTERY, "warning"), (15, BATTERY, "warning"),
    (14.9, BATTERY, "critical"), (50, VOLTAGE, "ok"), (57, VOLTAGE, "warning"), (59, VOLTAGE, "critical"),
    (43, VOLTAGE, "warning"), (39, VOLTAGE, "critical"), (float("nan"), VOLTAGE, "critical"), (1e9, None, "ok"),
])
def test_levels(value, hint, level):
    assert level_of(value, hint) == level


COMMANDS = {"PanTiltCamera": {"pointCamera": {"abortable": True, "suspendable": False, "description": "point",
                                              "parameters": [
    {"name": "pan", "type": "RAPID_FLOAT", "unit": "rad", "min": -3.05, "max": 3.05, "allowed": [], "default": 0,
     "has_default": True, "description": ""},
    {"name": "mode", "type": "RAPID_STRING", "unit": None, "min": None, "max": None, "allowed": ["a", "b"],
     "default": "a", "has_default": True, "description": ""},
    {"name": "tiles", "type": "RAPID_INT", "unit": None, "min": 1, "max": 64, "allowed": [], "default": None,
     "has_default": False, "description": ""}]}}}
LIVE = {"availableSubsystemTypes": [{"name": "PanTiltCamera", "commands": [
    {"name": "pointCamera", "abortable": True, "suspendable": False,
     "parameters": [{"key": "pan", "type": "RAPID_FLOAT"}, {"key": "mode", "type": "RAPID_STRING"},
                    {"key": "tiles", "type": "RAPID_INT"}]}]}],
    "availableSubsystems": [{"name": "PanCam", "subsystemTypeName": "PanTiltCamera"}]}


def _hints() -> Hints:
    return Hints([AssetHints("K10Red", "K10Red", COMMANDS, {"PanCam": "PanTiltCamera"}, {"batteryCharge": BATTERY},
                             ["RapidWorkbench"])])


def test_live_dictionary_gets_the_descriptors_hints():
    got = _hints().commands_for("K10Red", LIVE)
    assert got["origin"] == "live" and got["sources"] == ["RapidWorkbench"]
    pan = got["subsystems"][0]["commands"][0]["parameters"][0]
    assert (pan["unit"], pan["min"], pan["max"], pan["default"]) == ("rad", -3.05, 3.05, 0)
    bare = Hints().commands_for("Other", LIVE)["subsystems"][0]["commands"][0]["parameters"][0]
    assert (bare["unit"], bare["min"], bare["has_default"]) == (None, None, False)
    assert Hints().commands_for("Other", None) == {"origin": None, "subsystems": [], "sources": []}


def _request(**kw):
    msg = {"partition": "K10Red", "subsystem": "PanCam", "command": "pointCamera", "source": "RapidWorkbench",
           "args": {"pan": "1.5", "mode": "b", "tiles": "8"}}
    msg.update(kw)
    return check(msg, _hints().commands_for("K10Red", LIVE), "K10Red")


def test_a_good_request_is_typed_and_defaults_fill_the_rest():
    req = _request()
    assert req.args == (("RAPID_FLOAT", 1.5), ("RAPID_STRING", "b"), ("RAPID_INT", 8)) and req.action == "QUEUE_BYPASS"
    assert _request(args={"tiles": "2"}).args == (("RAPID_FLOAT", 0.0), ("RAPID_STRING", "a"), ("RAPID_INT", 2))


def test_queue_actions_name_their_target_and_delete_carries_no_arguments():
    """INSERT and REPLACE are checked as any command, with the queued cmdId they act on;
    a DELETE names its target's command and sends no arguments (nothing to check)."""
    req = _request(action="INSERT", target="RapidWorkbench-7")
    assert (req.action, req.target, len(req.args)) == ("QUEUE_INSERT", "RapidWorkbench-7", 3)
    assert _request(action="REPLACE", target="x").action == "QUEUE_REPLACE"
    with pytest.raises(Refused, match="pan: 4 not in"):
        _request(action="REPLACE", target="x", args={"pan": "4"})
    gone = _request(action="DELETE", target="RapidWorkbench-7", args={"pan": "4"})
    assert (gone.action, gone.target, gone.args, gone.command) == ("QUEUE_DELETE", "RapidWorkbench-7", (),
                                                                   "pointCamera")
    assert _request().target == ""


@pytest.mark.parametrize("kw,why", [
    ({"source": ""}, "choose a command source"), ({"source": "x" * 40}, "at most 31 bytes"),
    ({"source": "bad\x1bsource"}, "printable"), ({"command": "nope"}, "not in the asset's command dictionary"),
    ({"args": {"pan": "4"}}, "pan: 4 not in [-3.05, 3.05]"), ({"args": {"pan": "x", "tiles": "1"}}, "not a RAPID_FLOAT"),
    ({"args": {"mode": "c", "tiles": "1"}}, "not one of a|b"), ({"args": {}}, "tiles: a value is needed"),
    ({"action": "SWAP"}, "unknown queue action"), ({"args": ["x"]}, "arguments must be an object"),
    ({"action": "DELETE"}, "DELETE acts on a queued command: choose it in the queue first"),
    ({"action": "REPLACE", "target": " "}, "REPLACE acts on a queued command"),
    ({"action": "APPEND", "target": "K10-1"}, "APPEND takes no target"), ({"action": "INSERT", "target": 5}, "a cmdId"),
    ({"action": "INSERT", "target": "x" * 64}, "at most 63 bytes"), ({"action": "DELETE", "target": "a\nb"}, "printable"),
])
def test_bad_requests_are_refused_with_the_reason(kw, why):
    with pytest.raises(Refused) as exc:
        _request(**kw)
    assert why in str(exc.value)


def _agent_state(value: float, assetName: str = "K10Red"):
    union = NS(discriminator=NS(name="RAPID_FLOAT"), value=value)
    return NS(hdr=NS(assetName=assetName, statusCode=0), values=[union])


def test_deltas_by_cursor_and_bounded_log():
    hub = Hub(_hints(), clock=lambda: 1000.0)
    hub.sample("K10Red", "rapid_agent_config", "rapid::AgentConfig",
               NS(hdr=NS(assetName="K10Red"), valueKeys=[NS(key="batteryCharge", value=NS(discriminator=NS(
                   name="RAPID_FLOAT"), value=0.0))]), 1.0)
    hub.sample("K10Red", "rapid_agent_state", "rapid::AgentState", _agent_state(20.0), 2.0)
    cursor, msgs = hub.delta(0)
    (k10,) = msgs
    assert k10["values"][0]["key"] == "batteryCharge" and k10["values"][0]["level"] == "warning"
    assert k10["points"] == [("agent/batteryCharge", 2.0, 20.0)] and k10["status"]["name"] == "K10Red"
    assert hub.delta(cursor) == (cursor, [])  # nothing new
    hub.sample("K10Red", "rapid_agent_state", "rapid::AgentState", _agent_state(10.0), 3.0)
    cursor2, (k10,) = hub.delta(cursor)
    assert k10["values"][0]["level"] == "critical" and k10["points"] == [("agent/batteryCharge", 3.0, 10.0)]
    assert "commands" not in k10  # unchanged sections are not sent again
    for i in range(LOG_LINES + 50):
        hub.sample("K10Red", "rapid_textmessage", "rapid::TextMessage",
                   NS(hdr=NS(assetName="K10Red"), level=NS(name="MSG_INFO"), category="c", message=f"line {i}"), 4.0)
    _, (k10,) = hub.delta(0)
    assert len(k10["log"]) == LOG_LINES and k10["log"][-1][3] == f"line {LOG_LINES + 49}"


# ---- issue 34: a rogue CommandConfig, decoy partitions, churning telemetry keys ------------------
SWAPPED = {**LIVE, "availableSubsystemTypes": [{"name": "PanTiltCamera", "commands": [
    {**LIVE["availableSubsystemTypes"][0]["commands"][0],
     "parameters": LIVE["availableSubsystemTypes"][0]["commands"][0]["parameters"][::-1]}]}]}


def _command_config(plain: dict):
    """A CommandConfig sample (attribute access, as decoded) from its plain form."""
    return NS(hdr=NS(assetName="K10Red"), availableSubsystemTypes=[
        NS(name=t["name"], commands=[NS(name=c["name"], abortable=c["abortable"], suspendable=c["suspendable"],
                                        parameters=[NS(key=p["key"], type=NS(name=p["type"])) for p in c["parameters"]])
                                     for c in t["commands"]]) for t in plain["availableSubsystemTypes"]],
        availableSubsystems=[NS(name=s["name"], subsystemTypeName=s["subsystemTypeName"])
                             for s in plain["availableSubsystems"]])


def _declared_hints() -> Hints:
    return Hints([AssetHints("K10Red", "K10Red", COMMANDS, {"PanCam": "PanTiltCamera"}, {}, ["RapidWorkbench"],
                             config=LIVE)])


def test_config_difference_names_the_parameters_in_their_order():
    assert config_difference(LIVE, LIVE) is None
    why = config_difference(LIVE, SWAPPED)
    assert why == ("PanTiltCamera/pointCamera parameters are tiles (INT), mode (STRING), pan (FLOAT); "
                   "the descriptor says pan (FLOAT), mode (STRING), tiles (INT)")
    moved = {**LIVE, "availableSubsystems": [{"name": "PanCam", "subsystemTypeName": "Other"}]}
    assert "subsystem PanCam has type Other" in config_difference(LIVE, moved)


class _Feed:
    def __init__(self) -> None:
        self.sent: list = []

    def send(self, req) -> str:
        self.sent.append(req)
        return "1-x"


def test_a_command_config_unlike_the_descriptor_refuses_every_send_until_its_writer_leaves():
    from rapidgen.monitor.sources import LiveSource
    hub, feed = Hub(_declared_hints()), _Feed()
    source = LiveSource(hub, feed, 0)  # type: ignore[arg-type]
    msg = {"type": "command", "ref": 1, "partition": "K10Red", "subsystem": "PanCam", "command": "pointCamera",
           "source": "RapidWorkbench", "args": {"pan": "1", "tiles": "3"}}
    hub.sample("K10Red", "rapid_command_config", "rapid::CommandConfig", _command_config(LIVE), 1.0, writer="real")
    assert source.handle(msg)["type"] == "sent" and len(feed.sent) == 1
    assert hub.delta(0)[1][0].get("alerts", []) == []
    hub.sample("K10Red", "rapid_command_config", "rapid::CommandConfig", _command_config(SWAPPED), 2.0, writer="rogue")
    got = source.handle(msg)
    assert got["type"] == "refused" and "pointCamera parameters are tiles (INT), mode (STRING), pan (FLOAT)" in \
        got["reason"] and "of writer rogue" in got["reason"], got
    assert len(feed.sent) == 1  # nothing written
    # the real writer republishing its own does not clear it
    hub.sample("K10Red", "rapid_command_config", "rapid::CommandConfig", _command_config(LIVE), 3.0, writer="real")
    assert source.handle(msg)["type"] == "refused"
    (k10,) = hub.delta(0)[1]
    assert k10["commands"]["refused"] and k10["alerts"][0] == k10["commands"]["refused"]
    assert k10["alerts"][1] == "2 writers publish rapid_command_config in this partition: real, rogue"
    hub.presence({"K10Red"}, {"real"})  # the rogue never listed by discovery (its tables full?): kept
    assert source.handle(msg)["type"] == "refused"
    hub.presence({"K10Red"}, {"real", "rogue"})
    hub.presence({"K10Red"}, {"real"})  # listed, then gone
    assert source.handle(msg)["type"] == "sent" and len(feed.sent) == 2
    assert hub.delta(0)[1][0].get("alerts", []) == []


def test_declared_assets_always_get_a_place_and_the_dropped_are_counted():
    hub = Hub(_declared_hints())
    for i in range(MAX_ASSETS + 5):
        hub.sample(f"Decoy{i:02d}", "rapid_agent_state", "rapid::AgentState", _agent_state(1.0, f"Decoy{i:02d}"), 1.0)
    hub.sample("Decoy00", "rapid_agent_state", "rapid::AgentState", _agent_state(1.0, "Decoy00"), 1.0)
    assert len(hub.assets) == MAX_ASSETS and hub.dropped_assets == 5
    hub.sample("K10Red", "rapid_agent_state", "rapid::AgentState", _agent_state(50.0), 2.0)
    assert "K10Red" in hub.assets and len(hub.assets) == MAX_ASSETS + 1
    assert any(n.startswith(f"5 partition(s) not shown (cap {MAX_ASSETS} besides the --asset ones")
               for n in hub.all_notes()), hub.all_notes()


def _churn(hub: Hub, gen: int, keys: int = 64, partition: str = "Churn") -> None:
    hub.sample(partition, "rapid_agent_config", "rapid::AgentConfig", NS(hdr=NS(assetName=partition), valueKeys=[
        NS(key=f"k{gen}_{i}", value=NS(discriminator=NS(name="RAPID_FLOAT"), value=0.0)) for i in range(keys)]),
        float(gen))
    union = NS(discriminator=NS(name="RAPID_FLOAT"), value=1.0)
    hub.sample(partition, "rapid_agent_state", "rapid::AgentState",
               NS(hdr=NS(assetName=partition, statusCode=0), values=[union] * keys), float(gen))


def test_churning_keys_keep_the_rows_the_config_declares():
    hub = Hub()
    for gen in range(200):
        _churn(hub, gen)
    a = hub.assets["Churn"]
    assert len(a.values) == 64 and a.rows_dropped == 199 * 64 and len(a.last_point) == 64
    assert {r["key"] for r in a.values.values()} == {f"k199_{i}" for i in range(64)}  # the newest stay
    (first,) = hub.delta(0)[1]  # a new page's first update
    assert len(first["values"]) == 64 and first["dropped"] == {"rows": 199 * 64, "cap": MAX_ROWS}
    assert {p[0] for p in first["points"]} <= {f"agent/{r['key']}" for r in first["values"]}
    assert any(n.startswith(f"{199 * 64} value row(s) dropped") for n in hub.all_notes())
    # a steady asset loses nothing
    for t in range(50):
        hub.sample("K10Red", "rapid_agent_state", "rapid::AgentState", _agent_state(float(t)), float(t))
    assert hub.assets["K10Red"].rows_dropped == 0


def test_rows_have_a_ceiling_whatever_the_configs_declare():
    hub = Hub()
    _churn(hub, 0, keys=400)
    a = hub.assets["Churn"]
    assert len(a.values) == MAX_ROWS and a.rows_dropped == 400 - MAX_ROWS


def test_gate_answers_its_own_names_and_checks_tokens():
    pytest.importorskip("aiohttp")
    from rapidgen.monitor.server import Gate
    g = Gate("127.0.0.1")
    for host in ("127.0.0.1:8765", "localhost:8765", "LOCALHOST:8765", "[::1]:8765"):
        assert g.host_ok(host, 8765), host
    for host in ("rebind.example:8765", "localhost.rebind.example:8765", "127.0.0.1:8766", "127.0.0.1", "", None,
                 "127.0.0.1:x", "[::1]x", "10.1.2.3:8765"):
        assert not g.host_ok(host, 8765), host
    assert g.host_ok("127.0.0.1", 80)  # no port: 80
    wide = Gate("0.0.0.0")  # any IP literal (cannot be rebound), never a name
    assert wide.host_ok("10.1.2.3:5", 5) and wide.host_ok("[fe80::1]:5", 5) and not wide.host_ok("evil.example:5", 5)
    assert Gate("192.0.2.1").host_ok("192.0.2.1:5", 5) and not Gate("192.0.2.1").host_ok("10.1.2.3:5", 5)
    token = g.token()
    assert g.token_ok(token) and token != g.token() and not Gate().token_ok(token)  # a key per process
    nonce, mac = token.split(".")
    for bad in (None, "", nonce, f"{nonce}.{'0' * 64}", f"{nonce}.{mac}.x", "é.é", "\udcff.x", token + "0"):
        assert not g.token_ok(bad), bad
