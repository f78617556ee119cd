"""Issue 34, live: a web page or a rogue on the domain must not command, mislead or blind the
operator through `rapidgen monitor`. K10's simulated bridge, the monitor and the rogues of
tests/monitor/hostile.py on loopback; the page in Debian's headless chromium.

- DNS rebinding (domain 36): requests whose Host is a foreign name are refused (421) with raw
  headers and in chromium with rebind.example mapped to 127.0.0.1; a WebSocket needs the
  page's Origin and its token (403); the page served on 127.0.0.1 works.
- A rogue CommandConfig (domain 36): K10's with pointCamera's parameters reversed, from a
  second writer; the page says so and a send is refused; a reader of rapid_command in
  K10Red (the rogue's) sees the command sent before the swap and none after.
- Churning telemetry keys (domain 36): rows stay at the config's 64, the dropped are counted
  on the page, a new page's first update is bounded.
- Decoys (domain 37): 66 decoy partitions and 260 topic names in one of them fill the
  watcher's and the page's limits before K10 starts; K10 (named with --asset) is shown and
  commandable, and the page says what was left out."""
from __future__ import annotations

import json
import re
import socket
import subprocess
import sys
import threading
import time
from urllib.parse import urlsplit

import pytest

from tests.monitor import browser
from tests.monitor import harness as H
from tests.runtime.live import BridgeProcess

DOMAIN, DECOY_DOMAIN = 36, 37
REBIND = "rebind.example"
TOKEN = re.compile(r'<meta name="monitor-token" content="([0-9a-f.]+)">')


class Hostile:
    """tests/monitor/hostile.py as a process; its stdout lines collected."""

    def __init__(self, pydirs, domain: int, modes: str, seconds: float = 240) -> None:
        self.proc = subprocess.Popen([sys.executable, "-m", "tests.monitor.hostile", str(pydirs["k10"]),
                                      H.ASSETS["k10"][1], str(domain), str(seconds), modes], cwd=H.ROOT,
                                     env=H.env(pydirs), stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True)
        self.lines: list[str] = []
        threading.Thread(target=self._read, daemon=True).start()
        H.until(lambda: "hostile ready" in self.lines or self.proc.poll() is not None, 60, what="hostile ready")
        assert "hostile ready" in self.lines, self.proc.stderr.read()[-3000:] if self.proc.stderr else ""

    def _read(self) -> None:
        for line in self.proc.stdout or ():
            self.lines.append(line.strip())

    def tell(self, line: str) -> None:
        assert self.proc.stdin is not None
        self.proc.stdin.write(line + "\n")
        self.proc.stdin.flush()

    def commands(self, name: str) -> list[str]:
        return [x for x in self.lines if x.startswith(f"command {name} ")]

    def stop(self) -> None:
        H.kill(self.proc)


def _start(pydirs, domain: int, hostile_modes: str, bridge_first: bool):
    """(bridge or None, hostile, monitor, driver): the pieces, each stopped by the caller."""
    bridge = None
    if bridge_first:
        bridge = BridgeProcess(pydirs["k10"], H.ASSETS["k10"][1], domain, "--sim-speed", "20")
        bridge.wait_ready()
    hostile = Hostile(pydirs, domain, hostile_modes)
    mon = H.Monitor(pydirs, domain)
    return bridge, hostile, mon


def _skip_without_tools() -> None:
    pytest.importorskip("cyclonedds")
    pytest.importorskip("aiohttp")
    why = browser.available()
    if why:
        pytest.skip(why)


@pytest.fixture(scope="module")
def pydirs(tmp_path_factory):
    _skip_without_tools()
    return H.generate(tmp_path_factory.mktemp("monitor-hostile-gen"))


@pytest.fixture(scope="module")
def rogue_net(pydirs):
    """K10 and a rogue that listens to K10's commands, swaps its CommandConfig on demand
    and churns its own partition's telemetry keys; the monitor; chromium able to resolve
    rebind.example to 127.0.0.1."""
    bridge = hostile = mon = driver = None
    try:
        bridge, hostile, mon = _start(pydirs, DOMAIN, "listen,swap,churn", bridge_first=True)
        driver = browser.chromium(extra=(f"--host-resolver-rules=MAP {REBIND} 127.0.0.1", "--no-proxy-server"))
        yield {"bridge": bridge, "hostile": hostile, "monitor": mon, "driver": driver}
    finally:
        H.quietly(lambda: driver.quit() if driver is not None else None)
        H.quietly(lambda: hostile.stop() if hostile is not None else None)
        H.quietly(lambda: print("monitor's stderr:", mon.stop()[2][-3000:]) if mon is not None else None)
        H.quietly(lambda: bridge.stop() if bridge is not None else None)


# ---- 1. DNS rebinding ------------------------------------------------------------------------
def _complete(data: bytes) -> bool:
    """A whole response: its headers and as many body bytes as Content-Length says."""
    head, sep, body = data.partition(b"\r\n\r\n")
    if not sep:
        return False
    m = re.search(rb"(?im)^content-length: *(\d+)", head)
    return m is None or len(body) >= int(m.group(1))


def _raw(url: str, host: str, path: str = "/", extra: dict | None = None) -> tuple[int, str]:
    """(status, body) of a GET sent with exactly these headers to the monitor's address."""
    u = urlsplit(url)
    head = {"Host": host, "Connection": "close", **(extra or {})}
    req = f"GET {path} HTTP/1.1\r\n" + "".join(f"{k}: {v}\r\n" for k, v in head.items()) + "\r\n"
    with socket.create_connection((u.hostname, u.port), timeout=10) as s:
        s.sendall(req.encode())
        data = b""
        while True:
            try:
                got = s.recv(65536)
            except socket.timeout:
                break
            if not got:
                break
            data += got
            if _complete(data):
                break  # (an accepted WebSocket, or a kept-alive refusal, stays open)
    status = int(data.split(b" ", 2)[1]) if data.startswith(b"HTTP/1.1 ") else 0
    return status, data.decode("utf-8", "replace")


def _upgrade(origin: str | None) -> dict:
    h = {"Upgrade": "websocket", "Connection": "Upgrade", "Sec-WebSocket-Version": "13",
         "Sec-WebSocket-Key": "dGhlIHNhbXBsZSBub25jZQ=="}
    if origin is not None:
        h["Origin"] = origin
    return h


def _token(url: str) -> str:
    status, body = _raw(url, urlsplit(url).netloc)
    assert status == 200, body[:300]
    m = TOKEN.search(body)
    assert m, body[:600]
    return m.group(1)


def test_foreign_host_origin_and_token_refused_with_raw_headers(rogue_net):
    url = rogue_net["monitor"].url
    port = urlsplit(url).port
    own, rebind = f"127.0.0.1:{port}", f"{REBIND}:{port}"
    token = _token(url)
    assert token != _token(url)  # one per page served
    ws = f"/ws?token={token}"
    # the rebinding attacker's requests: its name with the served port, its own origin
    status, body = _raw(url, rebind)
    assert status == 421 and "DNS rebinding" in body and "monitor-token" not in body
    assert _raw(url, rebind, ws, _upgrade(f"http://{rebind}"))[0] == 421
    assert _raw(url, rebind, "/static/monitor.js")[0] == 421
    assert _raw(url, f"localhost.{REBIND}:{port}")[0] == 421
    assert _raw(url, f"127.0.0.1:{port + 1}")[0] == 421  # the port must be the one served
    # the loopback names are answered
    for host in (own, f"localhost:{port}", f"[::1]:{port}"):
        assert _raw(url, host)[0] == 200, host
    # the WebSocket: Origin required and equal to the page's, the page's token required
    assert _raw(url, own, ws, _upgrade(None))[0] == 403
    assert _raw(url, own, ws, _upgrade(f"http://{rebind}"))[0] == 403
    assert _raw(url, own, "/ws", _upgrade(f"http://{own}"))[0] == 403
    forged = token.split(".")[0] + "." + "0" * 64
    assert _raw(url, own, f"/ws?token={forged}", _upgrade(f"http://{own}"))[0] == 403
    assert _raw(url, own, ws, _upgrade(f"http://{own}"))[0] == 101  # all three right: accepted


def test_rebinding_page_in_chromium_cannot_open_the_socket(rogue_net):
    """The page loaded through rebind.example (mapped to 127.0.0.1) gets the refusal, not the
    monitor; a WebSocket opened from that origin (even with a real token) never opens and
    its command never reaches the wire; the same browser on 127.0.0.1 works."""
    from selenium.webdriver.common.by import By
    d, mon, hostile = rogue_net["driver"], rogue_net["monitor"], rogue_net["hostile"]
    port = urlsplit(mon.url).port
    token = _token(mon.url)
    d.get(f"http://{REBIND}:{port}/")
    assert "DNS rebinding" in d.find_element(By.TAG_NAME, "body").text
    assert d.find_elements(By.ID, "assets") == []
    before = len(hostile.commands("requestControl"))
    got = d.execute_async_script("""
        const done = arguments[arguments.length - 1];
        const ws = new WebSocket("ws://" + location.host + "/ws?token=" + arguments[0]);
        let opened = false;
        ws.onopen = () => { opened = true; ws.send(JSON.stringify({type: "command", ref: 1, partition: "K10Red",
            subsystem: "AccessControl", command: "requestControl", source: "RapidWorkbench", args: {}})); };
        ws.onmessage = ev => { if (JSON.parse(ev.data).type === "sent") done("sent"); };
        ws.onclose = () => done(opened ? "opened, then closed" : "refused");
        setTimeout(() => done(opened ? "opened" : "pending"), 8000);""", token)
    assert got == "refused", got
    assert d.execute_script("return fetch('/').then(r => r.status)") == 421
    # the normal page in the same browser: connected, K10 listed
    d.get(mon.url)
    H.until(lambda: d.find_element(By.ID, "conn").text == "connected", 20, what="the page's socket")
    H.until(lambda: d.find_elements(By.CSS_SELECTOR, "nav button[data-partition='K10Red']"), 30, what="K10Red")
    time.sleep(1.0)  # the rebinding page's command would be on the wire by now
    assert len(hostile.commands("requestControl")) == before


# ---- 2. a rogue CommandConfig --------------------------------------------------------------
def test_swapped_command_config_is_shown_and_its_commands_refused(rogue_net):
    from selenium.webdriver.common.by import By
    d, mon, hostile = rogue_net["driver"], rogue_net["monitor"], rogue_net["hostile"]
    d.get(mon.url)
    H.select(d, "K10Red", "commands")
    H.choose_source(d, "RapidWorkbench")
    H.until(lambda: d.find_element(By.CSS_SELECTOR, "form[data-command='PanCam/pointCamera'] button.send")
            .is_enabled(), 20, what="send enabled")
    assert H.wait_completed(d, H.send(d, "AccessControl/requestControl"))[-1].startswith("COMPLETED OK")
    # before the swap: pan=1.0 tilt=0.3 reaches the wire as [1.0, 0.3] (the listener sees commands)
    ok = H.send(d, "PanCam/pointCamera", {"pan": "1.0", "tilt": "0.3"})
    assert H.wait_completed(d, ok)[-1].startswith("COMPLETED OK"), H.ack_chips(d, ok)
    first = H.until(lambda: hostile.commands("pointCamera"), 15, what="pointCamera on the wire")
    assert first[0].startswith("command pointCamera [1.0, 0.30"), first
    assert H.texts(d, "#alerts .alert") == []
    hostile.tell("swap")
    H.until(lambda: "swapped" in hostile.lines, 15, what="the rogue's CommandConfig")
    alerts = H.until(lambda: (lambda t: t if len(t) >= 2 else None)(H.texts(d, "#alerts .alert")), 20,
                     what="the mismatch shown")
    assert "PanTiltCamera/pointCamera parameters are tilt (FLOAT), pan (FLOAT); the descriptor says pan (FLOAT), " \
           "tilt (FLOAT)" in alerts[0], alerts
    assert alerts[1].startswith("2 writers publish rapid_command_config in this partition"), alerts
    assert "not sendable" in d.find_element(By.ID, "commands-refused").text
    assert "warning" in d.find_element(By.CSS_SELECTOR, "nav button[data-partition='K10Red']").text
    # a send is refused by the server, with the reason; nothing reaches the wire
    form = d.find_element(By.CSS_SELECTOR, "form[data-command='PanCam/pointCamera']")
    H.fill(form, {"pan": "1.0", "tilt": "0.3"})
    form.find_element(By.CSS_SELECTOR, "button.send").click()
    answer = form.find_element(By.CSS_SELECTOR, ".answer")
    H.until(lambda: "not sent" in answer.text, 15, what="the refusal")
    assert "differs from the --asset descriptor's" in answer.text and "pointCamera" in answer.text, answer.text
    noop = d.find_element(By.CSS_SELECTOR, "form[data-command='Admin/noOp']")
    noop.find_element(By.CSS_SELECTOR, "button.send").click()
    H.until(lambda: "not sent" in noop.find_element(By.CSS_SELECTOR, ".answer").text, 15, what="noOp refused")
    time.sleep(2.0)  # what was written would have been read by now (the first took well under this)
    assert hostile.commands("pointCamera") == first and hostile.commands("noOp") == [], hostile.lines[-5:]


# ---- 5. churning telemetry keys --------------------------------------------------------------
def test_churning_keys_keep_the_page_bounded(rogue_net):
    import asyncio

    import aiohttp
    d, mon = rogue_net["driver"], rogue_net["monitor"]
    d.get(mon.url)
    H.select(d, "Churn", "telemetry")
    dropped = """const e = document.getElementById('rows-dropped'); return e ? +e.dataset.rows : 0;"""
    H.until(lambda: d.execute_script(dropped) > 64 * 8, 60, what="eight generations of keys dropped")
    rows = d.execute_script("return document.querySelectorAll('#values tr[data-key]').length")
    assert rows == 64, rows
    assert "row(s) dropped" in d.find_element("id", "rows-dropped").text
    assert any("value row(s) dropped" in n for n in H.texts(d, "#notes div"))

    async def first_update():
        url = mon.url
        async with aiohttp.ClientSession() as s:
            async with s.get(url) as r:
                token = TOKEN.search(await r.text()).group(1)
            async with s.ws_connect(url + "ws?token=" + token, origin=url.rstrip("/")) as ws:
                for _ in range(10):
                    msg = json.loads((await ws.receive()).data)
                    if msg["type"] == "delta":
                        return msg
        raise AssertionError("no delta")
    msg = asyncio.run(first_update())
    churn = next(a for a in msg["assets"] if a["partition"] == "Churn")
    assert len(churn["values"]) == 64 and churn["dropped"]["rows"] > 64 * 8
    kept = {f"{r['group']}/{r['key']}" for r in churn["values"]}
    assert {p[0] for p in churn.get("points", [])} <= kept


# ---- 3. decoys -------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def decoy_net(pydirs):
    """66 decoy partitions and a 260-topic flood seen by the monitor before K10 starts."""
    bridge = hostile = mon = driver = None
    try:
        _b, hostile, mon = _start(pydirs, DECOY_DOMAIN, "decoys,flood", bridge_first=False)
        driver = browser.chromium()
        driver.get(mon.url)
        decoys = "return [...document.querySelectorAll('nav button')].filter(b => b.dataset.partition.startsWith('Decoy'))" \
                 ".length"
        H.until(lambda: driver.execute_script(decoys) == 64, 90, what="64 decoys on the page")
        hostile.tell("flood")
        H.until(lambda: any("readers (topic, partition, QoS) not opened" in x for x in H.texts(driver, "#notes div")),
                90, what="the watcher's reader cap reached")
        bridge = BridgeProcess(pydirs["k10"], H.ASSETS["k10"][1], DECOY_DOMAIN, "--sim-speed", "20")
        bridge.wait_ready()
        yield {"bridge": bridge, "hostile": hostile, "monitor": mon, "driver": driver}
    finally:
        H.quietly(lambda: driver.quit() if driver is not None else None)
        H.quietly(lambda: hostile.stop() if hostile is not None else None)
        H.quietly(lambda: print("monitor's stderr:", mon.stop()[2][-3000:]) if mon is not None else None)
        H.quietly(lambda: bridge.stop() if bridge is not None else None)


def test_declared_asset_is_shown_and_commandable_beside_decoys_and_a_flood(decoy_net):
    from selenium.webdriver.common.by import By
    d = decoy_net["driver"]
    assets = d.execute_script("return [...document.querySelectorAll('nav button')].map(b => b.dataset.partition)")
    assert len([p for p in assets if p.startswith("Decoy")]) == 64, len(assets)  # the limits were full
    H.select(d, "K10Red", "commands")
    H.choose_source(d, "RapidWorkbench")
    H.until(lambda: d.find_element(By.CSS_SELECTOR, "form[data-command='Admin/noOp'] button.send").is_enabled(), 30,
            what="K10's forms")
    assert H.wait_completed(d, H.send(d, "AccessControl/requestControl"))[-1].startswith("COMPLETED OK")
    H.select(d, "K10Red", "telemetry")
    H.until(lambda: H.value_cell(d, "agent/batteryCharge"), 30, what="K10's telemetry read")
    notes = H.texts(d, "#notes div")
    assert any(re.match(r"\d+ readers \(topic, partition, QoS\) not opened \(cap 256\)", n) for n in notes), notes
    assert any(re.match(r"2 partition\(s\) not read", n) for n in notes), notes
