"""`rapidgen monitor --foxglove PORT` (docs/foxglove.md): K10's simulated bridge on domain 70
(loopback) served over Foxglove's WebSocket protocol; a client built on Foxglove's own
@foxglove/ws-protocol under Node (tests/node/ws_client.js) connects, subscribes to every
channel, decodes each message with the advertised schema; the RAPID channels' values equal the
samples an independent raw reader (tests/record/tap.py) took off the wire, decoded by the
same omgidl reader, and the derived ones validate against @foxglove/schemas and equal their
RAPID sample. A foreign Host and a browser Origin not allowed are refused; a client that
stops reading is dropped while another keeps receiving."""
from __future__ import annotations

import json
import re
import socket
import subprocess
import sys
import threading
import time

import pytest

from tests.node.runner import run_json
from tests.record.test_record import K10, PKG, PYDIR, RAPIDGEN, ROOT, Proc, BridgeProcess, ENV

DOMAIN = 70
CMD = [*RAPIDGEN, "cmd", K10, "--domain", str(DOMAIN), "--source", "RapidWorkbench", "--timeout", "20"]


@pytest.fixture(scope="module")
def served():
    pytest.importorskip("cyclonedds")
    pytest.importorskip("aiohttp")
    mon = Proc([*RAPIDGEN, "monitor", "--asset", K10, "--domain", str(DOMAIN), "--foxglove", "0"])
    bridge = None
    try:
        mon.wait_for("Foxglove WebSocket server")
        port = int(re.search(r"ws://127\.0\.0\.1:(\d+)/", "".join(mon.err)).group(1))
        bridge = BridgeProcess(PYDIR, PKG, DOMAIN, "--sim-speed", "4")
        bridge.wait_ready()
        yield {"port": port, "mon": mon}
    finally:
        if bridge is not None:
            bridge.stop()
        mon.end()


def _upgrade(port: int, host: str, origin: str | None) -> str:
    """The status line of a WebSocket upgrade with these headers."""
    with socket.create_connection(("127.0.0.1", port), timeout=10) as s:
        req = (f"GET / HTTP/1.1\r\nHost: {host}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
               "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n"
               "Sec-WebSocket-Protocol: foxglove.websocket.v1\r\n" + (f"Origin: {origin}\r\n" if origin else "") + "\r\n")
        s.sendall(req.encode())
        return s.recv(4096).decode("latin-1").split("\r\n", 1)[0]


def test_host_and_origin_rules(served):
    port = served["port"]
    assert " 101 " in _upgrade(port, f"127.0.0.1:{port}", None)
    assert " 101 " in _upgrade(port, f"localhost:{port}", None)
    assert " 421 " in _upgrade(port, f"evil.example:{port}", None)  # DNS rebinding
    assert " 421 " in _upgrade(port, f"127.0.0.1:{port + 1}", None)
    assert " 403 " in _upgrade(port, f"127.0.0.1:{port}", "https://evil.example")  # a browser page elsewhere


def test_every_channel_decodes_with_its_advertised_schema_values_equal_to_the_wire(served, tmp_path):
    port = served["port"]
    tap = Proc([sys.executable, "-m", "tests.record.tap", str(PYDIR), PKG, str(DOMAIN), str(tmp_path / "tap.json")])
    tap.wait_for("tap ready", where="out")
    after_tap = time.time_ns()  # a served sample stamped later was on the wire for the tap too
    result: dict = {}
    client = threading.Thread(target=lambda: result.update(run_json("ws_client.js", f"ws://127.0.0.1:{port}/", "15")))
    client.start()
    time.sleep(1.5)
    for argv in (["AccessControl", "requestControl"], ["PanCam", "takePicture", "mode=stereo"],
                 ["Mobility", "simpleMove", "frame=site", "xyt=1,1,0.5"]):
        res = subprocess.run(CMD + argv, cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=120)
        assert res.returncode == 0, res.stderr[-1000:]
    client.join(timeout=60)
    time.sleep(0.5)
    assert tap.end() == 0
    got = result
    assert got["subprotocol"] == "foxglove.websocket.v1" and got["failed"] == [] and got["invalid"] == []
    enc = {c["topic"]: (c["encoding"], c["schemaEncoding"], c["schemaName"]) for c in got["channels"]}
    assert enc["/K10Red/rapid_position_sample"] == ("cdr", "omgidl", "rapid::PositionSample")
    assert enc["/K10Red/rapid_ext_arc_gps_sample"] == ("cdr", "omgidl", "rapid::ext::arc::GpsSample")
    for topic, schema in (("/K10Red/rapid_position_sample/transform", "foxglove.FrameTransform"),
                          ("/K10Red/rapid_position_sample/pose", "foxglove.PoseInFrame"),
                          ("/K10Red/rapid_ext_arc_gps_sample/location", "foxglove.LocationFix"),
                          ("/K10Red/rapid_imagesensor_sample-panCamLeft/image", "foxglove.CompressedImage")):
        assert enc[topic] == ("json", "jsonschema", schema)
        assert got["messages"].get(topic), topic

    # RAPID channels: the same samples the tap took off the wire (decoded by the same omgidl reader)
    with open(tmp_path / "tap.json", encoding="utf-8") as fh:
        tapped = json.load(fh)
    wire = tmp_path / "wire.json"
    checked = 0
    for topic in ("rapid_position_sample", "rapid_ext_arc_gps_sample", "rapid_agent_state"):
        served_msgs = [m["message"] for m in got["messages"].get(f"/K10Red/{topic}", [])
                       if int(m["timestamp"]) > after_tap]
        assert len(served_msgs) >= 3, topic
        advertised = next(c for c in got["channels"] if c["topic"] == f"/K10Red/{topic}")
        wire.write_text(json.dumps({"schema": advertised,
                                    "hex": tapped[topic]}), encoding="utf-8")
        from_tap = run_json("decode_hex.js", str(wire))
        stamps = {json.dumps(m, sort_keys=True) for m in from_tap}
        for m in served_msgs:  # every served sample is one the tap saw (the tap started first)
            assert json.dumps(m, sort_keys=True) in stamps, (topic, m)
            checked += 1
    assert checked >= 9

    # derived channels equal their RAPID sample (same timestamp: the same take)
    rapid = {m["timestamp"]: m["message"] for m in got["messages"]["/K10Red/rapid_position_sample"]}
    for d in got["messages"]["/K10Red/rapid_position_sample/pose"]:
        r = rapid[d["timestamp"]]
        p = d["message"]["pose"]["position"]
        assert [p["x"], p["y"], p["z"]] == r["pose"]["xyz"] and d["message"]["frame_id"] == "site"
    fixes = {m["timestamp"]: m["message"] for m in got["messages"]["/K10Red/rapid_ext_arc_gps_sample"]}
    for d in got["messages"]["/K10Red/rapid_ext_arc_gps_sample/location"]:
        r = fixes[d["timestamp"]]
        assert (d["message"]["latitude"], d["message"]["longitude"]) == (r["latitude"], r["longitude"])


def test_a_client_that_stops_reading_is_dropped_and_others_go_on(capfd):
    """The server alone (rapidgen.monitor.foxglove_server, real sockets, 256 KiB queue budget): a raw
    client subscribes and never reads; a second one reads everything. Messages of 64 KiB are
    published one at a time, each once the reader has it: the silent client is dropped (its
    socket closed, said on stderr), the reader gets every message, before and after."""
    import asyncio
    import os
    import struct as st

    aiohttp = pytest.importorskip("aiohttp")
    from aiohttp import web

    from rapidgen.monitor.foxglove_server import FoxgloveServer

    async def main():
        server = FoxgloveServer(budget=256 << 10)
        server.loop = asyncio.get_running_loop()
        runner = web.AppRunner(server.app(), access_log=None)
        await runner.setup()
        site = web.TCPSite(runner, "127.0.0.1", 0)
        await site.start()
        port = runner.addresses[0][1]
        cid = server.add_channel("/bulk", "json", "foxglove.Log", "{}", "jsonschema")
        # the silent client: a tiny receive buffer, subscribes, never reads again
        silent = socket.socket()
        silent.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
        silent.connect(("127.0.0.1", port))
        silent.sendall((f"GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\n"
                        "Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
                        "Sec-WebSocket-Version: 13\r\nSec-WebSocket-Protocol: foxglove.websocket.v1\r\n\r\n").encode())
        body = json.dumps({"op": "subscribe", "subscriptions": [{"id": 7, "channelId": cid}]}).encode()
        mask = os.urandom(4)
        silent.sendall(bytes([0x81, 0x80 | len(body)]) + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(body)))
        got = []
        async with aiohttp.ClientSession() as session:
            async with session.ws_connect(f"ws://127.0.0.1:{port}/", protocols=("foxglove.websocket.v1",)) as ws:
                await ws.send_json({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": cid}]})

                async def read():
                    async for m in ws:
                        if m.type == aiohttp.WSMsgType.BINARY:
                            got.append(st.unpack_from("<Q", m.data, 5)[0])
                reader = asyncio.create_task(read())
                await asyncio.sleep(0.5)  # both subscriptions in
                sent, drop_at = 0, 0
                while sent < 400 and (drop_at == 0 or sent < drop_at + 20):
                    server.publish(cid, sent + 1, b"x" * (64 << 10))
                    sent += 1
                    for _ in range(2000):  # the reader has it before the next one goes
                        if len(got) >= sent:
                            break
                        await asyncio.sleep(0.005)
                    if server.dropped and drop_at == 0:
                        drop_at = sent
                reader.cancel()
        await runner.cleanup()
        return server, sent, got, drop_at, silent

    server, sent, got, drop_at, silent = asyncio.run(main())
    assert server.dropped == 1 and 0 < drop_at < 400, (server.dropped, drop_at)
    assert got == list(range(1, sent + 1))  # the reader: every message, in order, 20 of them after the drop
    assert sent >= drop_at + 20
    assert "dropped: too slow: more than 262144 bytes queued" in capfd.readouterr().err
    silent.settimeout(10)
    try:  # the silent client's connection was closed: what is left in it ends
        while silent.recv(1 << 16):
            pass
    except ConnectionResetError:
        pass
    silent.close()


@pytest.mark.parametrize("argv,said", [
    (["--foxglove", "70000"], "--foxglove 70000 is outside 0..65535"),
    (["--foxglove", "0", "--replay", "x.mcap"], "--foxglove serves the live domain"),
    (["--foxglove", "0", "--foxglove-queue", "abc"], "'abc' is not a size"),
])
def test_usage_errors(argv, said):
    res = subprocess.run([*RAPIDGEN, "monitor", *argv], cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=60)
    assert res.returncode == 2 and said in res.stderr and "Traceback" not in res.stderr, res.stderr
