"""Drive the Fast DDS TCP exchange of test_wan.py (usually inside a private network namespace).

    tcp_exchange.py PROBE SITE_A_XML SITE_B_XML DOMAIN ATTEMPTS [--no-server]

Per attempt: `fastdds discovery` from site A's rapid_wan_tcp_server profile (unless
--no-server), an echo program with site A's rapid_wan_tcp profile (it accepts TCP
connections), then a ping program with site B's (it only connects out). Exit 0 as soon
as one attempt's ping got its echoes back; 1 when none did. Every process has a
deadline and is killed before the next attempt.
"""
import os
import signal
import subprocess
import sys
import time

PROFILE = "RapidReliableQos"


def start(args, timeout):
    return subprocess.Popen(["timeout", "-k", "1", str(timeout), *args], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, start_new_session=True)


def wait_line(proc, text, timeout):
    """Read proc's output until a line holds text; the lines read."""
    import selectors

    lines, end = [], time.monotonic() + timeout
    sel = selectors.DefaultSelector()
    sel.register(proc.stdout, selectors.EVENT_READ)
    while time.monotonic() < end:
        if not sel.select(max(0.0, end - time.monotonic())):
            break
        line = proc.stdout.readline()
        if not line:
            break
        lines.append(line)
        if text in line:
            break
    sel.close()
    return lines


def stop(proc):
    try:
        os.killpg(proc.pid, signal.SIGKILL)  # `timeout` and the program it runs
    except ProcessLookupError:
        pass
    try:
        out = proc.stdout.read() or ""
    except ValueError:
        out = ""
    proc.wait(5)
    return out


def attempt(probe, a, b, domain, server_wanted, count):
    procs, log = [], []
    try:
        if server_wanted:
            server = start(["fastdds", "discovery", "-x", f"rapid_wan_tcp_server@{a}"], 30)
            procs.append(server)
            lines = wait_line(server, "Server is running", 10)
            log += ["server: " + x for x in lines]
            if not any("Server is running" in x for x in lines):
                return False, log
        echo = start([probe, "echo", a, domain, "rapid_wan_tcp", PROFILE, "14", str(count)], 20)
        procs.append(echo)
        log += ["echo: " + x for x in wait_line(echo, "ready", 10)]
        ping = start([probe, "ping", b, domain, "rapid_wan_tcp", PROFILE, "5" if server_wanted else "3",
                      str(count)], 15)
        procs.append(ping)
        try:
            out, _ = ping.communicate(timeout=16)
        except subprocess.TimeoutExpired:
            ping.kill()
            out, _ = ping.communicate()
        log += ["ping: " + x for x in out.splitlines(True)]
        return ping.returncode == 0, log
    finally:
        for p in procs:
            name = p.args[4].rsplit("/", 1)[-1] + (" " + p.args[5] if len(p.args) > 5 else "")
            log += [f"{name}: " + x for x in stop(p).splitlines(True)]


def main(argv):
    probe, a, b, domain, attempts = argv[1], argv[2], argv[3], argv[4], int(argv[5])
    server_wanted = "--no-server" not in argv
    for k in range(1, attempts + 1):
        ok, log = attempt(probe, a, b, domain, server_wanted, 5)
        sys.stdout.write("".join(log))
        print(f"attempt {k}: {'exchanged' if ok else 'no exchange'}", flush=True)
        if ok:
            return 0
    return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
