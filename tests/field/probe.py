"""UDP probes for the emulator's own test: `echo PORT` answers every datagram (inside the
asset namespace); `send ADDRESS PORT COUNT INTERVAL [LINGER]` sends numbered datagrams, waits LINGER s
(default 3) for the last answers, then prints
one JSON line: the round trip of each answered one and how often each number came back."""
from __future__ import annotations

import json
import socket
import struct
import sys
import time


def echo(port: int) -> None:
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("0.0.0.0", port))
    print("ready", flush=True)
    while True:
        data, peer = s.recvfrom(2048)
        s.sendto(data, peer)


def send(address: str, port: int, count: int, interval: float) -> None:
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.setblocking(False)
    sent: dict[int, float] = {}
    rtts: dict[int, float] = {}
    copies: dict[int, int] = {}
    order: list[int] = []
    n, next_at = 0, time.monotonic()
    deadline = None
    while True:
        now = time.monotonic()
        if n < count and now >= next_at:
            sent[n] = now
            s.sendto(struct.pack("!I", n) + b"x" * 60, (address, port))
            n, next_at = n + 1, next_at + interval
            if n == count:
                deadline = now + float(sys.argv[6]) if len(sys.argv) > 6 else now + 3.0  # answers on their way
        if deadline is not None and now > deadline:
            break
        try:
            data, _ = s.recvfrom(2048)
        except BlockingIOError:
            time.sleep(0.001)
            continue
        k = struct.unpack("!I", data[:4])[0]
        copies[k] = copies.get(k, 0) + 1
        order.append(k)
        rtts.setdefault(k, time.monotonic() - sent[k])
    print(json.dumps({"sent": count, "rtts": rtts, "copies": copies, "order": order}))


if __name__ == "__main__":
    if sys.argv[1] == "echo":
        echo(int(sys.argv[2]))
    else:
        send(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5]))
