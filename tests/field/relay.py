"""The link emulator's relay: a user-space process holding one TUN device in each of two
network namespaces (ground, asset). Every IP packet one side sends to the other is read
from that side's TUN and written to the other's after the direction's delay (fixed +
uniform jitter), unless it is lost or the link is cut; it may be duplicated or held back
(reordered). The kernel has no netem here, so this is the whole link.

Run by tests/field/link.py: `python relay.py CONFIG.json`; control lines on stdin
(`cut`, `restore`, `stats`, `profile JSON`, `quit`), one JSON answer per line on stdout.
RTPS DATA/DATA_FRAG submessages are recognised so that retransmissions (a writer's
sequence number sent again) can be counted: the retransmissions the bench reports."""
from __future__ import annotations

import ctypes
import fcntl
import heapq
import json
import os
import random
import select
import struct
import sys
import time

CLONE_NEWNET = 0x40000000
TUNSETIFF = 0x400454CA
IFF_TUN, IFF_NO_PI = 0x0001, 0x1000
SPDP_WRITER = bytes.fromhex("000100c2")
DIRECTIONS = ("up", "down")  # up: ground -> asset; down: asset -> ground


def open_tun(netns: str, name: str) -> int:
    """A file descriptor on TUN device `name` inside network namespace `netns` (setns for
    this thread only long enough to attach; the fd stays bound to that namespace)."""
    libc = ctypes.CDLL(None, use_errno=True)
    home = os.open("/proc/self/ns/net", os.O_RDONLY)
    target = os.open(f"/run/netns/{netns}", os.O_RDONLY)
    try:
        if libc.setns(target, CLONE_NEWNET) != 0:
            raise OSError(ctypes.get_errno(), f"setns {netns}")
        fd = os.open("/dev/net/tun", os.O_RDWR | os.O_NONBLOCK)
        fcntl.ioctl(fd, TUNSETIFF, struct.pack("16sH", name.encode(), IFF_TUN | IFF_NO_PI))
    finally:
        libc.setns(home, CLONE_NEWNET)
        os.close(target)
        os.close(home)
    return fd


def rtps_keys(packet: bytes) -> list[tuple]:
    """(destination, writer GUID, sequence number, fragment) of each DATA/DATA_FRAG in an
    IPv4/UDP RTPS packet; [] for anything else. Heartbeats, ACKNACKs and gaps are not data;
    participant announcements (SPDP) are re-sent by design and left out."""
    if len(packet) < 28 or packet[0] >> 4 != 4 or packet[9] != 17:
        return []
    ihl = (packet[0] & 15) * 4
    rtps = packet[ihl + 8:]
    if len(rtps) < 20 or rtps[:4] != b"RTPS":
        return []
    # address, port and (INFO_DST) participant: one copy per reader locator is no resend,
    # nor a durable writer's history sent to a new participant on a port an old one had
    locator = packet[16:20] + packet[ihl + 2:ihl + 4]
    dest, prefix, pos, keys = locator, rtps[8:20], 20, []
    while pos + 4 <= len(rtps):
        kind, flags = rtps[pos], rtps[pos + 1]
        size = int.from_bytes(rtps[pos + 2:pos + 4], "little" if flags & 1 else "big")
        body = rtps[pos + 4:pos + 4 + (size or len(rtps))]
        if kind in (0x15, 0x16) and len(body) >= 20 and body[8:12] != SPDP_WRITER:  # DATA, DATA_FRAG
            end = "little" if flags & 1 else "big"
            writer = prefix + body[8:12]
            sn = (int.from_bytes(body[12:16], end, signed=True) << 32) | int.from_bytes(body[16:20], end)
            frag = int.from_bytes(body[20:24], end) if kind == 0x16 and len(body) >= 24 else None
            keys.append((dest, writer, sn, frag))
        if kind == 0x0E and len(body) >= 12:  # INFO_DST: later submessages go to this participant
            dest = locator + body[:12]
        if kind == 0x0C and len(body) >= 12:  # INFO_SRC: later submessages are another participant's
            prefix = body[-12:]
        if size == 0:
            break
        pos += 4 + size
    return keys


class Relay:
    def __init__(self, config: dict) -> None:
        self.fds = {"up": open_tun(config["ground_ns"], config["ground_tun"]),
                    "down": open_tun(config["asset_ns"], config["asset_tun"])}
        self.out = {"up": self.fds["down"], "down": self.fds["up"]}
        self.profile = config["profile"]
        self.rng = random.Random(config.get("seed", 23))
        self.cut = False
        self.trace = open(config["trace"], "w", encoding="ascii") if config.get("trace") else None  # every packet
        self.t0 = time.monotonic()
        # (start, end) seconds after start: the link is down in between
        self.schedule = [tuple(w) for w in config.get("cuts", [])]
        self.queue: list[tuple[float, int, str, bytes]] = []
        self.seq = 0
        self.seen: dict[str, set] = {d: set() for d in DIRECTIONS}
        self.counts = {d: dict(received=0, forwarded=0, lost=0, cut=0, duplicated=0, reordered=0, bytes=0,
                               rtps_data=0, retransmitted=0) for d in DIRECTIONS}

    def down(self, now: float) -> bool:
        at = now - self.t0
        return self.cut or any(a <= at < b for a, b in self.schedule)

    def accept(self, direction: str, packet: bytes, now: float) -> None:
        c, p = self.counts[direction], self.profile[direction]
        c["received"] += 1
        if self.trace:
            self.trace.write(f"{direction} {now - self.t0:.3f} {packet.hex()}\n")
        for key in rtps_keys(packet):  # counted as sent, whatever the link then does
            c["rtps_data"] += 1
            if key in self.seen[direction]:
                c["retransmitted"] += 1
            else:
                self.seen[direction].add(key)
        if self.down(now):
            c["cut"] += 1
            return
        if self.rng.random() < p.get("loss", 0.0):
            c["lost"] += 1
            return
        copies = 2 if self.rng.random() < p.get("duplicate", 0.0) else 1
        c["duplicated"] += copies - 1
        for _ in range(copies):
            delay = p.get("delay", 0.0) + self.rng.uniform(-1, 1) * p.get("jitter", 0.0)
            if self.rng.random() < p.get("reorder", 0.0):  # held back: later packets overtake it
                delay += p.get("reorder_gap", 0.05)
                c["reordered"] += 1
            self.seq += 1
            heapq.heappush(self.queue, (now + max(0.0, delay), self.seq, direction, packet))

    def release(self, now: float) -> None:
        while self.queue and self.queue[0][0] <= now:
            _, _, direction, packet = heapq.heappop(self.queue)
            try:
                os.write(self.out[direction], packet)
            except OSError:  # the other side's interface is down or gone: the packet is lost
                self.counts[direction]["lost"] += 1
                continue
            self.counts[direction]["forwarded"] += 1
            self.counts[direction]["bytes"] += len(packet)

    def control(self, line: str) -> bool:
        word, _, rest = line.strip().partition(" ")
        if word == "cut":
            self.cut = True
        elif word == "restore":
            self.cut = False
        elif word == "profile":
            self.profile = json.loads(rest)
        elif word == "quit":
            return False
        reply = dict(self.counts, cut=self.down(time.monotonic()), queued=len(self.queue))
        sys.stdout.write(json.dumps(reply) + "\n")
        sys.stdout.flush()
        return True

    def run(self) -> None:
        by_fd = {self.fds["up"]: "up", self.fds["down"]: "down"}
        stdin = sys.stdin.fileno()
        buffered = b""
        sys.stdout.write(json.dumps({"ready": True}) + "\n")
        sys.stdout.flush()
        while True:
            now = time.monotonic()
            wait = max(0.0, self.queue[0][0] - now) if self.queue else 1.0
            ready, _, _ = select.select([*by_fd, stdin], [], [], wait)
            now = time.monotonic()
            for fd in ready:
                if fd == stdin:
                    chunk = os.read(stdin, 4096)
                    if not chunk:
                        return
                    buffered += chunk
                    while b"\n" in buffered:
                        line, buffered = buffered.split(b"\n", 1)
                        if not self.control(line.decode()):
                            return
                    continue
                for _ in range(64):  # drain what is waiting, a bounded batch per wake-up
                    try:
                        packet = os.read(fd, 65536)
                    except BlockingIOError:
                        break
                    self.accept(by_fd[fd], packet, now)
            self.release(time.monotonic())


if __name__ == "__main__":
    with open(sys.argv[1], encoding="utf-8") as fh:
        Relay(json.load(fh)).run()
