"""A field link between two network namespaces, `ground` and `asset`, joined only through a
user-space relay (tests/field/relay.py) that delays, drops, duplicates, reorders and cuts
packets per direction. Each namespace has `lo` and one point-to-point TUN device:
ground 10.231.0.1 <-> asset 10.231.0.2; nothing else, so DDS traffic cannot leave them.

    with Link(LUNAR) as link:
        bridge = link.popen("asset", [sys.executable, "-m", "pkg.bridge", ...])
        link.run("ground", ["rapidgen", "cmd", ...])
        link.cut(); ...; link.restore()
        print(link.stats())     # per direction: received, forwarded, lost, cut, duplicated, ...

Needs root (ip netns, /dev/net/tun). Namespaces are named rgf<pid>-<n>-<side>, removed on
close (and, at the next start, any left by a process that no longer runs).
`python -m tests.field.link --profile lunar` sets one up for a person to try."""
from __future__ import annotations

import itertools
import json
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

GROUND, ASSET = "10.231.0.1", "10.231.0.2"
ADDRESS = {"ground": GROUND, "asset": ASSET}
TUN = "rgftun"
_serial = itertools.count()


def direction(delay: float = 0.0, jitter: float = 0.0, loss: float = 0.0, duplicate: float = 0.0,
              reorder: float = 0.0, reorder_gap: float = 0.05) -> dict:
    """One direction's behaviour: seconds of delay +- uniform jitter, probabilities of loss,
    duplication and of being held back reorder_gap seconds (overtaken by later packets)."""
    return dict(delay=delay, jitter=jitter, loss=loss, duplicate=duplicate, reorder=reorder, reorder_gap=reorder_gap)


def symmetric(**kw) -> dict:
    return {"up": direction(**kw), "down": direction(**kw)}


PROFILES = {
    "clear": symmetric(),
    "lunar": symmetric(delay=1.3, jitter=0.02, loss=0.05),   # issue 23: the Moon, 2.6 s round trip
    "lossy": symmetric(delay=0.05, jitter=0.01, loss=0.1, duplicate=0.02, reorder=0.05),
}
LUNAR = PROFILES["lunar"]


def rtt(profile: dict) -> float:
    """The profile's round trip without jitter (seconds)."""
    return profile["up"]["delay"] + profile["down"]["delay"]


def _ip(*args: str, ns: str | None = None, check: bool = True) -> subprocess.CompletedProcess:
    argv = (["ip", "netns", "exec", ns] if ns else []) + ["ip", *args]
    res = subprocess.run(argv, capture_output=True, text=True)
    if check and res.returncode:
        raise RuntimeError(f"{' '.join(argv)}: {res.stderr.strip()}")
    return res


def remove_stale() -> None:
    """Namespaces an earlier link left behind when its process died without closing it."""
    listed = _ip("netns", "list", check=False).stdout
    for name in re.findall(r"^(rgf(\d+)-\d+-(?:ground|asset))\b", listed, re.M):
        if not Path(f"/proc/{name[1]}").exists():
            _ip("netns", "delete", name[0], check=False)


class Link:
    def __init__(self, profile: dict, cuts: list[tuple[float, float]] = (), seed: int = 23,
                 trace: str | None = None) -> None:
        self.profile, self.cuts, self.seed, self.trace = profile, [tuple(c) for c in cuts], seed, trace
        n = next(_serial)
        self.ns = {side: f"rgf{os.getpid()}-{n}-{side}" for side in ("ground", "asset")}
        self.relay: subprocess.Popen | None = None
        self.children: list[subprocess.Popen] = []
        self.tmp = tempfile.TemporaryDirectory(prefix="rgf-link-")

    # -- life cycle ------------------------------------------------------------------
    def __enter__(self) -> "Link":
        try:
            self.start()
        except BaseException:
            self.close()
            raise
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def start(self) -> None:
        remove_stale()
        for side, ns in self.ns.items():
            _ip("netns", "add", ns)
            _ip("link", "set", "lo", "up", ns=ns)
            for key in ("all", "default"):  # IPv4 only: no router solicitations counted as traffic
                subprocess.run(["ip", "netns", "exec", ns, "sysctl", "-qw", f"net.ipv6.conf.{key}.disable_ipv6=1"],
                               capture_output=True)
            _ip("tuntap", "add", "dev", TUN, "mode", "tun", ns=ns)
            peer = ASSET if side == "ground" else GROUND
            _ip("addr", "add", ADDRESS[side], "peer", peer, "dev", TUN, ns=ns)
            _ip("link", "set", TUN, "up", "multicast", "on", ns=ns)
            _ip("route", "add", "224.0.0.0/4", "dev", TUN, ns=ns)  # lan: multicast crosses the link too
        config = Path(self.tmp.name) / "relay.json"
        config.write_text(json.dumps(dict(ground_ns=self.ns["ground"], asset_ns=self.ns["asset"], ground_tun=TUN,
                                          asset_tun=TUN, profile=self.profile, cuts=self.cuts, seed=self.seed,
                                          trace=self.trace)))
        self.relay = subprocess.Popen([sys.executable, str(Path(__file__).with_name("relay.py")), str(config)],
                                      stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        first = self.relay.stdout.readline()
        if not first.startswith('{"ready"'):
            raise RuntimeError(f"link relay did not start: {first!r}")

    def close(self) -> None:
        for p in self.children:
            if p.poll() is None:
                p.kill()
            p.wait()
        if self.relay is not None and self.relay.poll() is None:
            try:
                self.relay.stdin.write("quit\n")
                self.relay.stdin.flush()
                self.relay.wait(timeout=5)
            except (OSError, subprocess.TimeoutExpired):
                self.relay.kill()
                self.relay.wait()
        for ns in self.ns.values():
            _ip("netns", "delete", ns, check=False)
        self.tmp.cleanup()

    # -- processes on either side ------------------------------------------------------
    def argv(self, side: str, argv: list[str]) -> list[str]:
        return ["ip", "netns", "exec", self.ns[side], *argv]

    def popen(self, side: str, argv: list[str], **kw) -> subprocess.Popen:
        """A process inside `side`'s namespace; killed at close if still running."""
        p = subprocess.Popen(self.argv(side, argv), **kw)
        self.children.append(p)
        return p

    def run(self, side: str, argv: list[str], **kw) -> subprocess.CompletedProcess:
        return subprocess.run(self.argv(side, argv), **kw)

    # -- the link itself -------------------------------------------------------------
    def _tell(self, line: str) -> dict:
        assert self.relay is not None and self.relay.poll() is None, "the relay is not running"
        self.relay.stdin.write(line + "\n")
        self.relay.stdin.flush()
        return json.loads(self.relay.stdout.readline())

    def cut(self) -> dict:
        """The link goes down in both directions: every packet sent meanwhile is lost."""
        return self._tell("cut")

    def restore(self) -> dict:
        return self._tell("restore")

    def set_profile(self, profile: dict) -> dict:
        self.profile = profile
        return self._tell("profile " + json.dumps(profile))

    def stats(self) -> dict:
        """Per direction ("up" ground->asset, "down"): received, forwarded, lost, cut,
        duplicated, reordered, bytes, rtps_data, retransmitted; plus cut and queued."""
        return self._tell("stats")


def main() -> int:
    import argparse
    import time
    ap = argparse.ArgumentParser(prog="python -m tests.field.link", description=__doc__.split("\n\n")[0])
    ap.add_argument("--profile", choices=sorted(PROFILES), default="lunar")
    ap.add_argument("--seconds", type=float, default=0, help="stay up this long (default: until Ctrl-C)")
    args = ap.parse_args()
    with Link(PROFILES[args.profile]) as link:
        print(f"link up ({args.profile}): ground {GROUND} in netns {link.ns['ground']}, asset {ASSET} in netns "
              f"{link.ns['asset']}\n  ip netns exec {link.ns['ground']} ping {ASSET}", flush=True)
        try:
            time.sleep(args.seconds or 10**9)
        except KeyboardInterrupt:
            pass
        print(json.dumps(link.stats(), indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
