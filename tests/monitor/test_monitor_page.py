"""`rapidgen monitor` in a real headless chromium (Debian's, through selenium and Debian's
chromedriver) against real simulated bridges on loopback (DDS domain 107): the page shows
K10 and Robonaut 2, a command sent from the page completes with its ack sequence shown, a
value past its threshold takes the declared level's colour, the map draws the traverse,
and a rogue writer's markup and script appear as text. Also the server's refusals (a
cross-origin WebSocket, a picture whose MIME type is not a picture's) and usage errors."""
from __future__ import annotations

import json
import re
from urllib.parse import quote
import subprocess
import sys

import pytest

from tests.monitor import browser
from tests.monitor import harness as H
from tests.monitor.rogue import ASSET as ROGUE_ASSET, NAME as ROGUE_NAME, PARTITION as ROGUE_PARTITION, TEXT as ROGUE_TEXT

DOMAIN = 107
K10_SPEED = 300  # battery 100 % -> below 15 % (critical) ~14 s after the bridge starts
# A test asset whose batteryCharge the test sets, with K10's thresholds (warning < 30, critical < 15)
LEVELS = """version: 1
asset: {name: K10Blue, kind: rover}
dds: {domain: 107}
idl: {rapid: %s}
telemetry:
  - kind: agent
    rate: 4
    values:
      - {key: batteryCharge, type: RAPID_FLOAT, unit: "%%", range: [0, 100], warning: {below: 30}, critical: {below: 15}}
"""
WARNING, CRITICAL = "rgb(230, 145, 0)", "rgb(210, 30, 30)"  # monitor.css --warning, --critical


@pytest.fixture(scope="module")
def live(tmp_path_factory):
    pytest.importorskip("cyclonedds")
    pytest.importorskip("aiohttp")
    why = browser.available()
    if why:
        pytest.skip(why)
    pydirs = H.generate(tmp_path_factory.mktemp("monitor-gen"))
    levels_yaml = tmp_path_factory.mktemp("monitor-levels") / "k10blue.yaml"
    levels_yaml.write_text(LEVELS % (H.ROOT / "specs" / "rapid"), encoding="utf-8")
    procs: list = []
    rogue = levels = None
    driver = None
    try:
        procs += H.bridges(pydirs, DOMAIN, k10_speed=K10_SPEED)
        rogue = subprocess.Popen([sys.executable, "-m", "tests.monitor.rogue", str(pydirs["k10"]), "rapid_k10red",
                                  str(DOMAIN), "120"], cwd=H.ROOT, env=H.env(pydirs), stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, text=True)
        assert rogue.stdout.readline().startswith("rogue ready"), rogue.stderr.read()[-2000:]
        levels = subprocess.Popen([sys.executable, "-m", "tests.monitor.levels", str(pydirs["k10"]), "rapid_k10red",
                                   str(DOMAIN), "K10Blue"], cwd=H.ROOT, env=H.env(pydirs), stdin=subprocess.PIPE,
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        assert levels.stdout.readline().startswith("levels ready"), levels.stderr.read()[-2000:]
        mon = H.Monitor(pydirs, DOMAIN, "--asset", str(levels_yaml))
        procs.append(mon)
        driver = browser.chromium()
        driver.get(mon.url)
        yield {"driver": driver, "monitor": mon, "pydirs": pydirs, "levels": levels}
    finally:  # each step alone: a failing one must not leave processes behind
        H.quietly(lambda: driver.quit() if driver is not None else None)
        for p in (rogue, levels):
            if p is not None:
                H.quietly(lambda p=p: H.kill(p))
        for p in procs:
            if isinstance(p, H.Monitor):
                H.quietly(lambda p=p: print("monitor's stderr:", p.stop()[2][-3000:]))  # shown when a test failed
        H.stop_all(procs)


def _cell(driver, key: str) -> dict | None:
    return H.value_cell(driver, key)


def test_serves_on_loopback_and_says_so(live):
    mon = live["monitor"]
    assert mon.url.startswith("http://127.0.0.1:")
    assert "127.0.0.1 only" in mon.second


def test_page_shows_k10_and_robonaut2(live):
    from selenium.webdriver.common.by import By
    d = live["driver"]
    for partition in ("K10Red", "Robonaut2"):
        button = H.until(lambda: d.find_elements(By.CSS_SELECTOR, f"nav button[data-partition='{partition}']"), 30,
                         what=partition)[0]
        assert partition in button.text and button.get_attribute("data-status") == "live"
    H.select(d, "Robonaut2", "telemetry")
    H.until(lambda: _cell(d, "agent/leftForceMagnitude"), 20, what="R2's force value")
    assert d.execute_script("return document.querySelectorAll(\"#values tr[data-key^='joint/']\").length") > 0
    H.select(d, "Robonaut2", "commands")
    H.until(lambda: d.find_elements(By.CSS_SELECTOR, "form[data-command='Neck/Setpoint for single joint']"), 20,
            what="R2's neck command form")
    # units, ranges and allowed values from the descriptor on K10's forms
    H.select(d, "K10Red", "commands")
    form = H.until(lambda: d.find_elements(By.CSS_SELECTOR, "form[data-command='PanCam/pointCamera']"), 20,
                   what="pointCamera")[0]
    pan = form.find_element(By.CSS_SELECTOR, "[name='pan']")
    assert (pan.get_attribute("type"), pan.get_attribute("min"), pan.get_attribute("max")) == ("number", "-3.05", "3.05")
    assert "rad" in form.text
    mode = d.find_element(By.CSS_SELECTOR, "form[data-command='PanCam/takePicture'] select[name='mode']")
    assert [o.get_attribute("value") for o in mode.find_elements(By.TAG_NAME, "option")] == ["left", "right", "stereo"]


@pytest.fixture(scope="module")
def driven(live):
    """Commands sent from K10's page: the source chosen, control taken, a drive; their acks."""
    from selenium.webdriver.common.by import By
    d = live["driver"]
    H.select(d, "K10Red", "commands")
    H.until(lambda: d.find_elements(By.CSS_SELECTOR, "form[data-command='Admin/noOp']"), 20, what="forms")
    disabled = all(not b.is_enabled() for b in d.find_elements(By.CSS_SELECTOR, "button.send"))
    H.choose_source(d, "RapidWorkbench")
    H.until(lambda: d.find_element(By.CSS_SELECTOR, "form[data-command='Admin/noOp'] button.send").is_enabled(), 5,
            what="send enabled")
    control = H.wait_completed(d, H.send(d, "AccessControl/requestControl"))
    H.until(lambda: d.find_elements(By.CSS_SELECTOR, "#access [data-controller='RapidWorkbench']"), 15,
            what="controller shown")
    drive = H.wait_completed(d, H.send(d, "Mobility/simpleMove", {"frame": "site", "xyt": "300,150,0"}))
    queued = H.wait_completed(d, H.send(d, "Admin/echo", {"text": "through the queue", "queue-action": "APPEND"}))
    return {"disabled before a source": disabled, "control": control, "drive": drive, "queued": queued}


def test_command_from_the_page_completes(live, driven):
    from selenium.webdriver.common.by import By
    d = live["driver"]
    assert driven["disabled before a source"], "commands must wait for a chosen source"
    assert driven["control"] == ["EXECUTING", "COMPLETED OK: control granted to RapidWorkbench"], driven
    assert driven["drive"][0] == "EXECUTING" and driven["drive"][-1].startswith("COMPLETED OK: arrived at 300"), driven
    assert driven["queued"] == ["QUEUED", "EXECUTING", "COMPLETED OK: through the queue"], driven
    # refused before sending: a value outside its range
    H.select(d, "K10Red", "commands")
    H.until(lambda: H.texts(d, "#queue [data-queue]") == ["state: idle"], 10, what="the queue idle again")
    form = d.find_element(By.CSS_SELECTOR, "form[data-command='PanCam/pointCamera']")
    H.fill(form, {"pan": "4"})
    form.find_element(By.CSS_SELECTOR, "button.send").click()
    answer = form.find_element(By.CSS_SELECTOR, ".answer")
    H.until(lambda: "not sent" in answer.text, 10, what="refusal")
    assert "pan" in answer.text and "3.05" in answer.text


def _queued(d) -> list[str]:
    """The cmdIds of the queue view's active and pending records, in order."""
    return d.execute_script("return [...document.querySelectorAll('#queue [data-record]')].map(e => e.dataset.record)")


def _click_record(d, cmd_id: str, button: str) -> None:
    from selenium.webdriver.common.by import By
    H.until(lambda: cmd_id in _queued(d), 15, what=f"{cmd_id} in the queue view")
    d.find_element(By.CSS_SELECTOR, f"#queue [data-record='{cmd_id}'] button.{button}").click()


def _final(d, cmd_id: str) -> str:
    return H.wait_completed(d, cmd_id)[-1]


def test_queue_actions_from_the_page(live, driven):
    """DELETE, REPLACE and INSERT from the queue view (K10 has control from `driven`): a long
    drive runs, two echoes wait; the last is deleted, the first replaced, a third inserted
    after the replacement; then the drive itself is deleted and the queue runs in that order."""
    from selenium.webdriver.common.by import By
    d = live["driver"]
    H.select(d, "K10Red", "commands")
    H.until(lambda: H.texts(d, "#queue [data-queue]") == ["state: idle"], 20, what="the queue idle")
    drive = H.send(d, "Mobility/simpleMove", {"frame": "site", "xyt": "300000,0,0", "queue-action": "APPEND"})
    H.until(lambda: "EXECUTING" in H.ack_chips(d, drive), 15, what="the drive running")
    second = H.send(d, "Admin/echo", {"text": "second", "queue-action": "APPEND"})
    third = H.send(d, "Admin/echo", {"text": "third", "queue-action": "APPEND"})
    H.until(lambda: _queued(d) == [drive, second, third], 15, what="drive, second, third queued")
    # DELETE the last: its own answer, and the target's
    _click_record(d, third, "delete")
    gone = H.until(lambda: d.find_element(By.ID, "queue-answer").get_attribute("data-cmdid"), 15, what="DELETE sent")
    assert _final(d, gone).startswith("COMPLETED OK: ") and _final(d, gone).endswith(" canceled")  # (ids shortened)
    assert _final(d, third).startswith("COMPLETED CANCELED: deleted by "), H.ack_chips(d, third)
    # REPLACE the second, chosen as the target in the queue view
    _click_record(d, second, "target")
    H.until(lambda: d.find_element(By.ID, "queue-target").get_attribute("data-target") == second, 5, what="target")
    replaced = H.send(d, "Admin/echo", {"text": "replaced", "queue-action": "REPLACE"})
    assert _final(d, second).startswith("COMPLETED CANCELED"), H.ack_chips(d, second)
    H.until(lambda: _queued(d) == [drive, replaced], 15, what="the replacement queued in its place")
    # INSERT after the replacement (the target went with the second command it named)
    assert d.find_element(By.ID, "queue-target").get_attribute("data-target") == ""
    _click_record(d, replaced, "target")
    inserted = H.send(d, "Admin/echo", {"text": "inserted", "queue-action": "INSERT"})
    H.until(lambda: _queued(d) == [drive, replaced, inserted], 15, what="inserted after the replacement")
    # the running drive deleted (abortable): the queue goes on in order
    _click_record(d, drive, "delete")
    assert _final(d, drive).startswith("COMPLETED CANCELED"), H.ack_chips(d, drive)
    assert _final(d, replaced) == "COMPLETED OK: replaced"
    assert _final(d, inserted) == "COMPLETED OK: inserted"
    H.until(lambda: H.texts(d, "#queue [data-queue]") == ["state: idle"], 20, what="the queue idle again")


def test_value_past_threshold_turns_the_declared_colour(live):
    d = live["driver"]
    levels = live["levels"]
    H.select(d, "K10Blue", "telemetry")
    for value, level, colour in (("50", "ok", None), ("25", "warning", WARNING), ("10", "critical", CRITICAL),
                                 ("60", "ok", None)):
        levels.stdin.write(value + "\n")
        levels.stdin.flush()
        cell = H.until(lambda: (lambda c: c if c is not None and c["text"] == value else None)(
            _cell(d, "agent/batteryCharge")), 20, what=f"batteryCharge {value}")
        assert cell["level"] == level, cell
        if colour is not None:
            assert cell["background"] == colour, cell
    # the simulated K10's own battery (draining 300 times faster) ends past its critical threshold
    H.select(d, "K10Red", "telemetry")
    cell = H.until(lambda: (lambda c: c if c is not None and c["level"] == "critical" else None)(
        _cell(d, "agent/batteryCharge")), 60, what="K10's batteryCharge critical")
    assert float(cell["text"]) < 15 and cell["background"] == CRITICAL, cell
    assert _cell(d, "agent/batteryVoltage")["level"] == "ok"


def test_map_shows_the_traverse(live, driven):
    from selenium.webdriver.common.by import By
    d = live["driver"]
    H.select(d, "K10Red", "map")
    H.until(lambda: int(d.find_element(By.ID, "map").get_attribute("data-points") or 0) >= 3, 30,
            what="3 traverse points")
    assert H.traverse_pixels(d) > 100


def test_plots_and_the_latest_picture_of_each_sensor(live):
    d = live["driver"]
    H.select(d, "K10Red", "telemetry")
    drawn = """const c = [...document.querySelectorAll('canvas.plot')].find(e => e.dataset.series === arguments[0]);
        if (!c) return 0; const x = c.getContext('2d').getImageData(0, 0, c.width, c.height).data; let n = 0;
        for (let i = 0; i < x.length; i += 4) if (x[i+3] > 100 && x[i+2] - x[i] > 80) n++; return n;  // the blue line"""
    H.until(lambda: d.execute_script(drawn, "agent/batteryCharge") > 20, 20, what="batteryCharge's plot drawn")
    H.select(d, "K10Red", "images")
    shown = """const f = [...document.querySelectorAll('figure')].find(e => e.dataset.sensor === arguments[0]);
        const i = f && f.querySelector('img'); return i && i.complete ? [i.naturalWidth, i.naturalHeight] : null;"""
    assert H.until(lambda: d.execute_script(shown, "HazCamFront"), 30, what="HazCam's picture") == [640, 480]
    caption = H.texts(d, "figcaption")
    assert any("HazCamFront (stereo-left) 640x480, image/png" in c for c in caption), caption


def test_hostile_strings_appear_as_text(live):
    d = live["driver"]
    H.select(d, ROGUE_PARTITION, "log")
    H.until(lambda: ROGUE_TEXT in H.texts(d, "#log .text"), 20, what="the rogue's log line")
    assert any(ROGUE_ASSET in t for t in H.texts(d, "nav button.selected"))
    H.select(d, ROGUE_PARTITION, "commands")
    H.until(lambda: ROGUE_NAME in "".join(H.texts(d, "#forms")), 20, what="the rogue's command names")
    H.select(d, ROGUE_PARTITION, "telemetry")
    H.until(lambda: ROGUE_TEXT in H.texts(d, "#values td.value"), 20, what="the rogue's value")
    H.select(d, "K10Red", "log")
    H.until(lambda: ROGUE_TEXT in H.texts(d, "#log .text"), 20, what="the rogue's line in K10's log")
    H.select(d, "K10Red", "commands")  # the rogue's commands to K10 (cmdId with markup) and K10's refusals
    acks = H.until(lambda: [t for t in H.texts(d, "#acks li") if ROGUE_NAME in t], 20, what="the rogue's commands")
    assert any("access violation" in t for t in acks), acks
    for made in ("#pwn", "#pwn-asset", "#pwn-name", "script:not([src])", "img[src='x']", "img[onerror]"):
        assert H.texts(d, made) == [], made
    assert d.title == "rapidgen monitor"


def test_screenshots_of_every_view(live, tmp_path):
    shots = H.screenshots(live["driver"], tmp_path)
    assert [p.name for p in shots] == ["monitor-telemetry.png", "monitor-map.png", "monitor-commands.png",
                                       "monitor-images.png", "monitor-log.png", "monitor-robonaut2.png"]
    for p in shots:
        width, height = H.check_png(p)
        assert width == 1360 and height > 600, (p, width, height)


def test_server_refuses_cross_origin_sockets_and_foreign_picture_types(live):
    import asyncio

    import aiohttp
    url = live["monitor"].url

    async def probe():
        async with aiohttp.ClientSession() as s:
            with pytest.raises(aiohttp.WSServerHandshakeError) as exc:
                await s.ws_connect(url + "ws", origin="http://evil.example")
            assert exc.value.status == 403
            async with s.get(url) as r:  # the page carries the token its WebSocket needs
                token = re.search(r'<meta name="monitor-token" content="([0-9a-f.]+)">', await r.text()).group(1)
            async with s.ws_connect(url + "ws?token=" + token, origin=url.rstrip("/")) as ws:
                hello = json.loads((await ws.receive()).data)
                assert hello["type"] == "hello" and hello["mode"] == "live"
                await ws.send_json({"type": "command", "partition": "K10Red", "subsystem": "Admin", "command": "noOp"})
                for _ in range(50):
                    got = json.loads((await ws.receive()).data)
                    if got["type"] == "refused":
                        assert "source" in got["reason"]
                        break
                else:
                    raise AssertionError("a command without a source was not refused")
            async with s.get(url) as r:
                assert "script-src 'self'" in r.headers["Content-Security-Policy"]
            async with s.get(url + "picture/K10Red/NoSuchCamera") as r:
                assert r.status == 404
            rogue_cam = url + "picture/" + quote(ROGUE_PARTITION, safe="") + "/RogueCam"
            for _ in range(100):  # the rogue's text/html "picture" is never served as a page
                async with s.get(rogue_cam) as r:
                    if r.status != 404:
                        assert r.status == 415 and "html" not in r.headers.get("Content-Type", ""), r.status
                        break
                await asyncio.sleep(0.1)
            else:
                raise AssertionError("the rogue's picture never arrived")
    asyncio.run(probe())


@pytest.mark.parametrize("argv,needle", [
    (["--port", "70000"], "--port 70000 is outside"),
    (["--bind", "not-an-address"], "is not an IP address"),
    (["--tick", "0"], "--tick must be"),
    (["--seconds", "-1"], "--seconds must be positive"),
])
def test_bad_options_are_usage_errors(argv, needle):
    res = subprocess.run([sys.executable, "-m", "rapidgen", "monitor", *argv], cwd=H.ROOT, capture_output=True,
                         text=True, timeout=60)
    assert res.returncode == 2 and needle in res.stderr and "Traceback" not in res.stderr, res.stderr


def test_missing_recording_is_an_input_error(tmp_path):
    res = subprocess.run([sys.executable, "-m", "rapidgen", "monitor", "--replay", str(tmp_path / "none.mcap")],
                         cwd=H.ROOT, capture_output=True, text=True, timeout=60)
    assert res.returncode == 1 and "no such file" in res.stderr and "Traceback" not in res.stderr


def test_wide_bind_warns():
    """--bind beyond loopback says who can reach the page before listening (here on a
    documentation address this machine does not have: nothing is exposed, exit 1)."""
    res = subprocess.run([sys.executable, "-m", "rapidgen", "monitor", "--bind", "192.0.2.1", "--port", "0",
                          "--seconds", "1", "--domain", str(DOMAIN + 1)], cwd=H.ROOT, capture_output=True, text=True,
                         timeout=120, env=H.env({"k10": H.ROOT / "generated" / "k10" / "python"}))
    assert "warning: the page will be served on 192.0.2.1" in res.stderr, res.stderr
    assert res.returncode == 1 and "cannot listen on 192.0.2.1" in res.stderr and "Traceback" not in res.stderr


def test_an_asset_whose_writers_leave_is_shown_gone(live):
    """Runs last: the test asset's process ends (EOF on its stdin); discovery sees its
    writers go and the page says so."""
    d = live["driver"]
    live["levels"].stdin.close()
    live["levels"].wait(timeout=30)
    status = """const b = [...document.querySelectorAll('nav button')].find(e => e.dataset.partition === arguments[0]);
        return b ? [b.dataset.status, b.textContent] : null;"""
    got = H.until(lambda: (lambda s: s if s and s[0] == "gone" else None)(d.execute_script(status, "K10Blue")), 30,
                  what="K10Blue shown gone")
    assert "gone (no writer left)" in got[1]
    assert d.execute_script(status, "K10Red")[0] == "live"
