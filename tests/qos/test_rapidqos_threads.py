"""RapidQos (the generated qos.py) from several threads at once: each caller gets its own
topic's profile. cyclonedds' QosProvider alone is not thread-safe (two threads asking at
once could get each other's profile: a sample writer came out TransientLocal)."""
from __future__ import annotations

import sys
import threading
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PAIRS = 1500


def test_concurrent_lookups_return_each_topics_own_profile():
    sys.path.insert(0, str(ROOT / "generated" / "k10" / "python"))
    try:
        from rapid_k10red.qos import RapidQos
    finally:
        sys.path.pop(0)
    qos = RapidQos()
    topics = ("rapid_position_sample", "rapid_position_config")
    expected = {t: qos.writer(t) for t in topics}
    assert expected[topics[0]] != expected[topics[1]]  # two different profiles
    wrong: list[str] = []

    def ask(topic: str, barrier: threading.Barrier) -> None:
        barrier.wait()
        if qos.writer(topic) != expected[topic]:
            wrong.append(topic)

    for _ in range(PAIRS):
        barrier = threading.Barrier(2)
        threads = [threading.Thread(target=ask, args=(t, barrier)) for t in topics]
        for th in threads:
            th.start()
        for th in threads:
            th.join()
    assert wrong == []
