"""What the monitor's tests, its screenshots and its bench share: K10's and Robonaut 2's
packages generated into a temporary folder, their simulated bridges, the monitor as a
process (its URL read from its first line), and the page in headless chromium.

Everything is on loopback: the generated packages' `local` transport (127.0.0.1 only)."""
from __future__ import annotations

import re
import subprocess
import sys
import time
from pathlib import Path

from tests.runtime.live import BridgeProcess, env_for

ROOT = Path(__file__).resolve().parents[2]
ASSETS = {"k10": ("specs/assets/k10.yaml", "rapid_k10red", "K10Red"),
          "robonaut2": ("specs/assets/robonaut2.yaml", "rapid_robonaut2", "Robonaut2")}
URL = re.compile(r"on (http://\S+/)")


def generate(out: Path) -> dict[str, Path]:
    """{asset: its generated python folder} (python and qos targets)."""
    dirs = {}
    for asset, (desc, _pkg, _name) in ASSETS.items():
        res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", desc, "--lang", "python,qos",
                              "-o", str(out / asset)], cwd=ROOT, capture_output=True, text=True, timeout=300)
        assert res.returncode == 0, res.stderr[-3000:]
        dirs[asset] = out / asset / "python"
    return dirs


def env(pydirs: dict[str, Path]) -> dict:
    """Loopback transport (K10's local.xml) for every process of ours."""
    return env_for(pydirs["k10"], ASSETS["k10"][1])


def bridges(pydirs: dict[str, Path], domain: int, k10_speed: float = 20.0) -> list[BridgeProcess]:
    out = [BridgeProcess(pydirs["k10"], ASSETS["k10"][1], domain, "--sim-speed", str(k10_speed)),
           BridgeProcess(pydirs["robonaut2"], ASSETS["robonaut2"][1], domain)]
    for b in out:
        b.wait_ready()
    return out


class Monitor:
    """`rapidgen monitor` as a process on a free port of 127.0.0.1."""

    def __init__(self, pydirs: dict[str, Path], domain: int, *extra: str) -> None:
        args = [sys.executable, "-m", "rapidgen", "monitor", "--domain", str(domain), "--port", "0",
                "--asset", ASSETS["k10"][0], "--asset", ASSETS["robonaut2"][0], *extra]
        self.proc = subprocess.Popen(args, cwd=ROOT, env=env(pydirs), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True)
        first = self.proc.stdout.readline() if self.proc.stdout else ""
        m = URL.search(first)
        if m is None:
            self.proc.kill()
            raise AssertionError(f"monitor did not start: {first!r} {self.proc.stderr.read()[-3000:] if self.proc.stderr else ''}")
        self.url = m.group(1)
        self.second = self.proc.stdout.readline() if self.proc.stdout else ""

    def stop(self) -> tuple[int, str, str]:
        if self.proc.poll() is None:
            self.proc.terminate()
        try:
            out, err = self.proc.communicate(timeout=20)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            out, err = self.proc.communicate()
        return self.proc.returncode, out, err


def until(pred, timeout: float, step: float = 0.1, what: str = "condition"):
    """pred()'s first truthy value, polled; AssertionError naming `what` after timeout."""
    end = time.monotonic() + timeout
    while True:
        got = pred()
        if got:
            return got
        if time.monotonic() > end:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(step)


# ---- the page ---------------------------------------------------------------------------------
def select(driver, partition: str, tab: str) -> None:
    """Click the asset (found by its partition, which may hold any character) and the tab."""
    from selenium.webdriver.common.by import By
    until(lambda: driver.execute_script("""
        const b = [...document.querySelectorAll('nav button')].find(e => e.dataset.partition === arguments[0]);
        if (b) b.click();
        return !!b;""", partition), 30, what=f"asset {partition} in the list")
    until(lambda: driver.find_elements(By.CSS_SELECTOR, f"#tabs button[data-tab='{tab}']"), 10,
          what=f"tab {tab}")[0].click()


def choose_source(driver, source: str) -> None:
    from selenium.webdriver.common.by import By
    box = driver.find_element(By.ID, "source")
    box.clear()
    box.send_keys(source)
    driver.find_element(By.ID, "source-use").click()


def fill(form, values: dict[str, str]) -> None:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import Select
    for name, value in values.items():
        field = form.find_element(By.CSS_SELECTOR, f"[name='{name}']")
        if field.tag_name == "select":
            Select(field).select_by_value(value)
        else:
            field.clear()
            field.send_keys(value)


def send(driver, command: str, values: dict[str, str] | None = None) -> str:
    """Fill and send `Subsystem/command`'s form; the cmdId the page says it was sent as."""
    from selenium.webdriver.common.by import By
    form = until(lambda: driver.find_elements(By.CSS_SELECTOR, f"form[data-command='{command}']"), 30,
                 what=f"form {command}")[0]
    fill(form, values or {})
    form.find_element(By.CSS_SELECTOR, "button.send").click()
    answer = form.find_element(By.CSS_SELECTOR, ".answer")
    until(lambda: answer.get_attribute("data-cmdid") or "not sent" in answer.text, 15, what=f"{command} sent")
    cmd_id = answer.get_attribute("data-cmdid")
    assert cmd_id, answer.text
    return cmd_id


def ack_chips(driver, cmd_id: str) -> list[str]:
    """The ack sequence the page shows for cmd_id (read in one script: the list is redrawn
    with every update, so element handles go stale)."""
    return driver.execute_script("""
        const li = [...document.querySelectorAll('#acks li')].find(e => e.dataset.cmdid === arguments[0]);
        return li ? [...li.querySelectorAll('.ack')].map(e => e.textContent) : [];""", cmd_id)


def texts(driver, selector: str) -> list[str]:
    """textContent of every element the selector finds, read in one script."""
    return driver.execute_script("return [...document.querySelectorAll(arguments[0])].map(e => e.textContent)",
                                 selector)


def value_cell(driver, key: str) -> dict | None:
    """{text, level, background} of a value's cell (read in one script, as above)."""
    return driver.execute_script("""
        const td = [...document.querySelectorAll('#values tr')].find(e => e.dataset.key === arguments[0]);
        const c = td && td.querySelector('td.value');
        return c ? {text: c.textContent, level: c.dataset.level, background: getComputedStyle(c).backgroundColor} : null;
        """, key)


def wait_completed(driver, cmd_id: str, timeout: float = 30) -> list[str]:
    return until(lambda: (lambda c: c if any(x.startswith("COMPLETED") for x in c) else None)(ack_chips(driver, cmd_id)),
                 timeout, what=f"COMPLETED ack of {cmd_id}")


def traverse_pixels(driver) -> int:
    """Pixels of the traverse colour on the map canvas."""
    return driver.execute_script("""
        const c = document.getElementById('map'); if (!c) return 0;
        const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data; let n = 0;
        for (let i = 0; i < d.length; i += 4) if (d[i] === 40 && d[i+1] === 90 && d[i+2] === 200) n++;
        return n;""")


def screenshots(driver, folder: Path, k10: str = "K10Red", r2: str = "Robonaut2") -> list[Path]:
    """One PNG per view: K10's telemetry, map, commands, images and log, R2's telemetry."""
    folder.mkdir(parents=True, exist_ok=True)
    shots = []
    for partition, tab, name in ((k10, "telemetry", "telemetry"), (k10, "map", "map"), (k10, "commands", "commands"),
                                 (k10, "images", "images"), (k10, "log", "log"), (r2, "telemetry", "robonaut2")):
        select(driver, partition, tab)
        driver.execute_script("window.scrollTo(0, 0)")
        time.sleep(1.0)  # two page updates: the view drawn with its latest data
        path = folder / f"monitor-{name}.png"
        driver.save_screenshot(str(path))
        shots.append(path)
    return shots


def quietly(step) -> None:
    """A cleanup step whose failure must not skip the next ones."""
    try:
        step()
    except Exception as exc:  # said, then the cleanup goes on
        print(f"cleanup: {type(exc).__name__}: {exc}", file=sys.stderr)


def stop_all(procs) -> None:
    for p in procs:
        try:
            p.stop()
        except Exception:  # keep stopping the others
            pass


def kill(proc: subprocess.Popen) -> None:
    if proc.poll() is None:
        proc.kill()
    if proc.stdin is not None and proc.stdin.closed:  # a test closed it already
        proc.stdin = None
    proc.communicate()



def check_png(path: Path, min_bytes: int = 10_000) -> tuple[int, int]:
    """(width, height) of a real, non-trivial PNG screenshot."""
    import struct
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) >= min_bytes, (path, len(data))
    return struct.unpack(">II", data[16:24])
