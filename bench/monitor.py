"""`rapidgen monitor`: the page's update latency, and the screenshots of docs/images.

    python bench/monitor.py                       latency: sample published -> visible in the DOM
    python bench/monitor.py --samples 200 --ticks 0.1,0.05,0.02
    python bench/monitor.py --screenshots docs/images   one PNG per view (K10 driving, R2)
    python bench/monitor.py --hostile 40          the page against issue 34's rogues (figures of docs/monitor.md)

Latency: a publisher in this process writes AgentState samples of a test asset (one
batteryCharge value each, a new value every 0.3 s, so a sample never waits behind another)
and notes the wall time just before each write; in Debian's headless chromium a
MutationObserver notes the wall time at which the page's value cell first shows that value.
Both clocks are this machine's. Everything on loopback (the generated `local` transport),
DDS domain 108.

--hostile S: K10 beside tests/monitor/hostile.py's rogues (DDS domain 38): the churning
keys for S seconds (the Churn asset's rows on the page, the rows dropped, a new page's first
update in bytes), then 66 decoy partitions and a 260-topic flood (the decoys shown, K10
shown and its requestControl from the page completed, the page's notes).
"""
from __future__ import annotations

import argparse
import importlib
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.monitor import browser  # noqa: E402
from tests.monitor import harness as H  # noqa: E402

DOMAIN = 108
ASSET = "BenchAsset"
DESCRIPTOR = """version: 1
asset: {name: BenchAsset, kind: other}
dds: {domain: 108}
idl: {rapid: %s}
telemetry:
  - kind: agent
    values:
      - {key: batteryCharge, type: RAPID_FLOAT, unit: "%%", range: [0, 100], warning: {below: 30}, critical: {below: 15}}
"""
OBSERVER = """
window.__seen = []; let last = null;
const look = () => {
  const tr = [...document.querySelectorAll('#values tr')].find(e => e.dataset.key === 'agent/batteryCharge');
  const td = tr && tr.querySelector('td.value');
  if (td && td.textContent !== last) { last = td.textContent; window.__seen.push([last, Date.now()]); }
};
new MutationObserver(look).observe(document.getElementById('view'), {childList: true, subtree: true, characterData: true});
"""


def _publisher(pydir: Path, package: str):
    sys.path.insert(0, str(pydir))
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.qos import Policy, Qos
    from cyclonedds.topic import Topic
    rapid = importlib.import_module(f"{package}.rapid")
    qos = importlib.import_module(f"{package}.qos").RapidQos()
    dp = DomainParticipant(DOMAIN)
    pub = Publisher(dp, qos=Qos(Policy.Partition([ASSET])))
    config = DataWriter(pub, Topic(dp, "rapid_agent_config", rapid.AgentConfig), qos=qos.writer("rapid_agent_config"))
    state = DataWriter(pub, Topic(dp, "rapid_agent_state", rapid.AgentState), qos=qos.writer("rapid_agent_state"))

    def hdr():
        return rapid.Header(srcName=ASSET, assetName=ASSET, timeStamp=time.time_ns() // 1000, statusCode=0, serial=1)

    def value(v: float):
        return rapid.ParameterUnion(discriminator=rapid.DataType.RAPID_FLOAT, value=v)
    config.write(rapid.AgentConfig(hdr=hdr(), agentTags=[], topics=["rapid_agent_state"], valueKeys=[
        rapid.KeyTypeValueTriple(key="batteryCharge", padding=0, value=value(0.0))]))

    def write(v: float) -> float:
        sample = rapid.AgentState(hdr=hdr(), values=[value(v)])
        t = time.time()
        state.write(sample)
        return t
    return (dp, config), write  # the config writer kept: its durable sample lives with it


def latency(samples: int, ticks: list[float]) -> None:
    with tempfile.TemporaryDirectory(prefix="bench-monitor-") as tmp:
        pydirs = H.generate(Path(tmp))
        os.environ.update(CYCLONEDDS_URI=H.env(pydirs)["CYCLONEDDS_URI"])
        desc = Path(tmp) / "bench.yaml"
        desc.write_text(DESCRIPTOR % (ROOT / "specs" / "rapid"), encoding="utf-8")
        _keep, write = _publisher(pydirs["k10"], H.ASSETS["k10"][1])
        print(f"monitor update latency, {samples} samples per tick (sample written -> its value in the page's DOM)")
        print(f"{'tick [s]':>9} {'p50 [ms]':>9} {'p90 [ms]':>9} {'max [ms]':>9} {'min [ms]':>9} {'seen':>6}")
        for tick in ticks:
            mon = H.Monitor(pydirs, DOMAIN, "--asset", str(desc), "--tick", str(tick))
            driver = browser.chromium()
            try:
                driver.get(mon.url)
                H.select(driver, ASSET, "telemetry")  # (its durable AgentConfig made it known)
                H.until(lambda: write(1.0) and H.value_cell(driver, "agent/batteryCharge"), 30, step=0.3,
                        what="the bench asset's value")  # the monitor's reader matched
                driver.execute_script(OBSERVER)
                sent = {}
                for i in range(samples):
                    v = 50.0 + (i + 1) * 0.01
                    sent[round(v, 2)] = write(v)
                    time.sleep(0.3)
                time.sleep(1.0)
                seen = {}
                for text, ms in driver.execute_script("return window.__seen"):
                    key = round(float(text), 2)
                    if key in sent and key not in seen:
                        seen[key] = ms / 1000 - sent[key]
                lat = sorted(x * 1000 for x in seen.values())
                q = statistics.quantiles(lat, n=10) if len(lat) >= 10 else [float("nan")] * 9
                print(f"{tick:>9g} {statistics.median(lat):>9.1f} {q[8]:>9.1f} {max(lat):>9.1f} {min(lat):>9.1f} "
                      f"{len(lat):>3}/{samples}", flush=True)
            finally:
                H.quietly(driver.quit)
                mon.stop()


def screenshots(folder: Path) -> list[Path]:
    """K10 driving three legs with a picture taken and its battery in warning, and R2;
    the same traffic recorded by `rapidgen record` and played back (`--replay`)."""
    with tempfile.TemporaryDirectory(prefix="bench-monitor-") as tmp:
        pydirs = H.generate(Path(tmp))
        recording = Path(tmp) / "k10-drive.mcap"
        procs: list = []
        driver = None
        recorder = None
        try:
            procs += H.bridges(pydirs, DOMAIN + 1, k10_speed=60)  # battery below 30 % after ~60 s
            recorder = subprocess.Popen([sys.executable, "-m", "rapidgen", "record", "--domain", str(DOMAIN + 1),
                                         "--asset", H.ASSETS["k10"][0], "-o", str(recording), "--quiet"], cwd=ROOT,
                                        env=H.env(pydirs), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            mon = H.Monitor(pydirs, DOMAIN + 1)
            procs.append(mon)
            driver = browser.chromium()
            driver.get(mon.url)
            H.select(driver, "K10Red", "commands")
            H.choose_source(driver, "RapidWorkbench")
            H.wait_completed(driver, H.send(driver, "AccessControl/requestControl"))
            for xyt in ("60,0,0", "60,60,1.57", "0,90,3.14"):
                H.wait_completed(driver, H.send(driver, "Mobility/simpleMove", {"frame": "site", "xyt": xyt}), 60)
            H.wait_completed(driver, H.send(driver, "PanCam/takePicture", {"mode": "left"}))
            H.send(driver, "Mobility/simpleMove", {"frame": "site", "xyt": "-40,60,0"})
            H.select(driver, "K10Red", "telemetry")
            H.until(lambda: (H.value_cell(driver, "agent/batteryCharge") or {}).get("level") == "warning", 120,
                    what="K10's battery in warning")
            shots = H.screenshots(driver, folder)
            recorder.terminate()  # SIGTERM: the file is closed with its index
            recorder.communicate(timeout=30)
            driver.quit()
            driver = None
            H.stop_all(procs)
            procs = [replay := H.Monitor(pydirs, DOMAIN + 1, "--replay", str(recording))]
            driver = browser.chromium()
            driver.get(replay.url)
            H.until(lambda: "replay of" in driver.find_element("id", "mode").text, 30, what="replay mode")
            driver.execute_script("""const s = document.getElementById('replay-slider'); s.value = '250';
                                     s.dispatchEvent(new Event('change'));
                                     if (document.getElementById('replay-play').textContent === 'pause')
                                       document.getElementById('replay-play').click();""")
            H.select(driver, "K10Red", "map")
            time.sleep(2.0)
            driver.save_screenshot(str(folder / "monitor-replay.png"))
            return shots + [folder / "monitor-replay.png"]
        finally:
            if recorder is not None:
                H.quietly(lambda: H.kill(recorder))
            if driver is not None:
                H.quietly(driver.quit)
            H.stop_all(procs)


def _first_update(url: str) -> str:
    """A new page's first delta (its JSON text), with the page's token."""
    import asyncio
    import re

    import aiohttp

    async def get() -> str:
        async with aiohttp.ClientSession() as s:
            async with s.get(url) as r:
                m = re.search(r'<meta name="monitor-token" content="([0-9a-f.]+)">', await r.text())
            assert m is not None, "no token in the page"
            async with s.ws_connect(url + "ws?token=" + m.group(1), origin=url.rstrip("/"),
                                    max_msg_size=1 << 30) as ws:
                while True:
                    text = (await ws.receive()).data
                    if '"type": "delta"' in text:
                        return text
    return asyncio.run(get())


def hostile(seconds: float) -> None:
    import json

    from tests.monitor.test_monitor_hostile import Hostile
    from tests.runtime.live import BridgeProcess
    domain = 38
    with tempfile.TemporaryDirectory(prefix="bench-monitor-") as tmp:
        pydirs = H.generate(Path(tmp))
        procs: list = []
        driver = None
        try:
            procs.append(BridgeProcess(pydirs["k10"], H.ASSETS["k10"][1], domain, "--sim-speed", "20"))
            procs[-1].wait_ready()
            churn = Hostile(pydirs, domain, "churn", seconds=seconds + 60)
            mon = H.Monitor(pydirs, domain)
            procs.append(mon)
            time.sleep(seconds)
            first = _first_update(mon.url)
            msg = json.loads(first)
            c = next(a for a in msg["assets"] if a["partition"] == "Churn")
            print(f"churn, {seconds:g} s (64 keys renamed 4 times a second): the page holds {len(c['values'])} rows "
                  f"of Churn, {c.get('dropped', {}).get('rows', 0)} dropped; a new page's first update "
                  f"{len(first)} bytes ({len(msg['assets'])} assets)", flush=True)
            churn.stop()
            flood = Hostile(pydirs, domain, "decoys,flood", seconds=300)
            driver = browser.chromium()
            driver.get(mon.url)
            others = "return [...document.querySelectorAll('nav button')].filter(b => " \
                     "!['K10Red', 'Robonaut2'].includes(b.dataset.partition)).length"  # (Churn holds one place)
            H.until(lambda: driver.execute_script(others) == 64, 120, what="64 undeclared assets on the page")
            flood.tell("flood")
            H.until(lambda: any("not opened" in n for n in H.texts(driver, "#notes div")), 120, what="readers capped")
            H.select(driver, "K10Red", "commands")
            H.choose_source(driver, "RapidWorkbench")
            final = H.wait_completed(driver, H.send(driver, "AccessControl/requestControl"))[-1]
            names = driver.execute_script("return [...document.querySelectorAll('nav button')].map(b => b.dataset.partition)")
            print(f"decoys: {sum(n.startswith('Decoy') for n in names)} decoy partitions on the page, K10Red "
                  f"{'shown' if 'K10Red' in names else 'MISSING'}; requestControl from the page: {final}")
            for n in H.texts(driver, "#notes div"):
                print("  note:", n)
            flood.stop()
        finally:
            if driver is not None:
                H.quietly(driver.quit)
            H.stop_all(procs)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--samples", type=int, default=100)
    p.add_argument("--ticks", default="0.1,0.02", help="the monitor's --tick values to measure, comma-separated")
    p.add_argument("--screenshots", metavar="DIR", help="write the views' screenshots to DIR instead")
    p.add_argument("--hostile", type=float, metavar="S", help="measure the page against issue 34's rogues instead "
                   "(S seconds of churning keys)")
    args = p.parse_args()
    why = browser.available()
    if why:
        print(f"bench/monitor.py: {why}", file=sys.stderr)
        return 1
    if args.screenshots:
        for path in screenshots(Path(args.screenshots)):
            print(path, H.check_png(path))
        return 0
    if args.hostile:
        hostile(args.hostile)
        return 0
    latency(args.samples, [float(t) for t in args.ticks.split(",")])
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
