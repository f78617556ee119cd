"""Issue 22, the runtime's half: Python's cyclonedds cannot encode an Ack.message over 128
characters, nor one with a lone surrogate (the ack is then lost), so the runtime clips every
message before it is written, whoever wrote it: its own reasons, the built-in commands'
results, handler results, progress texts and handler errors. No DDS: K10's tables and
generated Ack class, the manager with an outbox that encodes each ack as the bridge would.
(The live half is the broken asset `long-ack-text`, which must pass every check.)"""
from __future__ import annotations

import importlib
import sys
import threading

import pytest

from rapid_runtime.acks import MESSAGE_BYTES, clip
from rapid_runtime.command import Cmd
from rapid_runtime.handlers import CommandFailed
from rapid_runtime.manager import CommandManager
from tests.runtime.live import SEEDS, python_dir
from tests.runtime.tables_of import tables

pytest.importorskip("cyclonedds")
ODD = "\udcff" + "\u00fc" * 150 + "\x00"  # a lone surrogate first, 301 bytes past it


@pytest.fixture(scope="module")
def rapid():
    sys.path.insert(0, str(python_dir("k10")))
    try:
        yield importlib.import_module(f"{SEEDS['k10']}.rapid")
    finally:
        sys.path.remove(str(python_dir("k10")))


class EncodingOutbox:
    """Encodes each ack with the generated class, as Bridge.ack does before writing."""

    def __init__(self, rapid) -> None:
        from rapid_runtime import messages as M
        self.rapid, self.M = rapid, M
        self.acks: dict[str, list[str]] = {}
        self.cond = threading.Condition()

    def ack(self, cmd, status, completed, message):
        sample = self.M.ack(self.rapid, cmd, status, completed, message)
        got = type(sample).deserialize(sample.serialize()).message  # raises where cyclonedds would
        with self.cond:
            self.acks.setdefault(cmd.cmd_id, []).append((status, got))
            self.cond.notify_all()

    def final(self, cmd_id: str) -> list[tuple[str, str]]:
        with self.cond:
            assert self.cond.wait_for(lambda: any(s == "ACK_COMPLETED" for s, _ in self.acks.get(cmd_id, [])), 10)
            return list(self.acks[cmd_id])

    def queue_state(self, *args):
        pass

    def access_state(self, *args):
        pass

    def retire(self, cmd):
        pass

    def log(self, text):
        pass


class Odd:
    """K10 handlers whose results, progress texts and failures are all ODD."""

    def pan_tilt_camera_take_picture(self, ctx, mode, exposure):
        ctx.progress(ODD)
        if mode == "right":
            raise CommandFailed(ODD)
        if mode == "stereo":  # a handler's bug: "handler error: ValueError: ..."
            raise ValueError(ODD)
        return ODD


def test_clip_bytes_surrogates_and_other_types():
    assert clip("x" * 200) == "x" * MESSAGE_BYTES
    assert clip("\u00e9" * 64) == "\u00e9" * 63  # never half a character
    assert clip("\udcffok") == "\ufffdok"  # a lone surrogate (and a NUL) becomes U+FFFD (issue 42)
    assert clip("a\x00b") == "a\ufffdb"
    assert clip(12) == "12" and clip("") == ""
    assert len(clip(ODD).encode()) <= MESSAGE_BYTES


def test_every_message_is_encodable(rapid):
    out = EncodingOutbox(rapid)
    m = CommandManager(tables("k10"), Odd(), out)
    n = iter(range(1, 100))

    def send(sub, name, args=(), src="RapidWorkbench"):
        cid = f"c{next(n)}"
        m.receive(Cmd(cid, src, sub, name, tuple(args), "QUEUE_BYPASS", "", "ground", "K10Red"))
        return out.final(cid)

    assert send("AccessControl", "requestControl")[-1][0] == "ACK_COMPLETED"
    for mode in ("left", "right", "stereo"):
        acks = send("PanCam", "takePicture", [("RAPID_STRING", mode), ("RAPID_FLOAT", 0.1)])
        texts = [t for s, t in acks if t]
        assert len(texts) == 2, acks  # the progress text and the final message, both written
        assert all(len(t.encode()) <= MESSAGE_BYTES for t in texts)
        assert texts[0].startswith("\ufffd\u00fc") and "\u00fc" in texts[1]
    echo = send("Admin", "echo", [("RAPID_STRING", ODD[:60])])  # a built-in's result
    assert echo[-1][1].startswith("\ufffd\u00fc") and len(echo[-1][1].encode()) <= MESSAGE_BYTES
    refused = send(ODD, ODD)  # the runtime's own reason, quoting wire text
    assert refused[-1][0] == "ACK_COMPLETED" and len(refused[-1][1].encode()) <= MESSAGE_BYTES


def test_a_write_that_fails_leaves_the_queue_moving(rapid):
    """Were an ack still refused, the command's state moves on (logged): the next runs."""
    class Refusing(EncodingOutbox):
        def ack(self, cmd, status, completed, message):
            if cmd.cmd_id == "bad":
                raise RuntimeError("refused")
            super().ack(cmd, status, completed, message)
    out = Refusing(rapid)
    m = CommandManager(tables("k10"), Odd(), out)
    m.receive(Cmd("rc", "RapidWorkbench", "AccessControl", "requestControl", (), "QUEUE_BYPASS", "", "g", "K10Red"))
    args = (("RAPID_STRING", "left"), ("RAPID_FLOAT", 0.1))
    m.receive(Cmd("bad", "RapidWorkbench", "PanCam", "takePicture", args, "QUEUE_APPEND", "", "g", "K10Red"))
    m.receive(Cmd("next", "RapidWorkbench", "PanCam", "takePicture", args, "QUEUE_APPEND", "", "g", "K10Red"))
    assert [s for s, _ in out.final("next")] == ["ACK_QUEUED", "ACK_EXECUTING", "ACK_EXECUTING", "ACK_COMPLETED"]
