"""Debian's headless chromium driven by selenium through Debian's chromedriver, named
explicitly so that selenium-manager never downloads a driver or a browser."""
from __future__ import annotations

import os
import shutil

CHROMIUM = ("/usr/bin/chromium", "/usr/lib/chromium/chromium")
DRIVER = ("/usr/bin/chromedriver", "/usr/lib/chromium/chromedriver")


def _first(paths) -> str | None:
    return next((p for p in paths if os.path.exists(p)), None)


def available() -> str | None:
    """None when the browser can be driven, else why not."""
    try:
        import selenium  # noqa: F401
    except ImportError:
        return "selenium is not installed (pip install selenium)"
    if _first(CHROMIUM) is None or _first(DRIVER) is None:
        return "Debian's chromium and chromium-driver are not installed (scripts/apt-packages.txt)"
    return None


def chromium(width: int = 1360, height: int = 900, extra: tuple[str, ...] = ()):
    """extra: more command-line flags (e.g. --host-resolver-rules for the rebinding test)."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    opts = webdriver.ChromeOptions()
    opts.binary_location = _first(CHROMIUM) or "chromium"
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                f"--window-size={width},{height}", "--hide-scrollbars", "--no-first-run",
                "--disable-extensions", "--disable-background-networking", "--disable-sync",
                "--disable-component-update", "--disable-default-apps", "--metrics-recording-only"):
        opts.add_argument(arg)
    for arg in extra:
        opts.add_argument(arg)
    service = Service(executable_path=_first(DRIVER) or shutil.which("chromedriver"))
    return webdriver.Chrome(service=service, options=opts)
