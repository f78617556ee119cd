"""QoS per RAPID topic, exactly as the generated QoS files define it.

`rapidgen generate ... --lang qos` writes, under qos/:

    topics.json             each topic -> its QoS profile key (library::profile); the partition
    dds-xml/rapid_qos.xml   the profiles, in OMG DDS-XML (what Cyclone's QoS provider loads)

RapidQos reads both: for a topic it returns what cyclonedds.qos_provider.QosProvider
returns for that topic's profile key. Every generated Python package has a `qos` module
whose RapidQos is this one with the package's own default folder:

    from rapid_k10red.qos import RapidQos

    qos = RapidQos()              # the package's own qos_files/ (asset packages), else <out>/qos
                                  # beside the package generated as <out>/python/<package>
    qos = RapidQos("out/qos")     # or a qos folder given explicitly
    publisher = Publisher(participant, qos=qos.publisher())            # the asset's partition
    writer = DataWriter(publisher, topic, qos=qos.writer("rapid_agent_config"))

It sets no transport: CYCLONEDDS_URI chooses that (qos/cyclonedds/local.xml is the
loopback-only one; cyclonedds_config() gives its path).
"""
from __future__ import annotations

import difflib
import json
import os
import threading
from typing import Any, Callable

from cyclonedds.core import DDSException
from cyclonedds.qos import Qos
from cyclonedds.qos_provider import QosProvider

__all__ = ["QosFilesMissing", "RapidQos", "RapidQosError", "UnknownTopic", "package_qos_dir"]

TOPICS_FILE = "topics.json"


class RapidQosError(Exception):
    """The QoS files cannot be used, or name no such thing (base of the errors below)."""


class QosFilesMissing(RapidQosError, FileNotFoundError):
    """topics.json, or a file it names, is not there."""


class UnknownTopic(RapidQosError, LookupError):
    """A topic that topics.json does not list."""


def package_qos_dir(package_dir: str) -> str:
    """A generated package's default qos folder: its own `qos_files/` (an asset package
    carries it, installed or not), else `<out>/qos` for a package generated as
    `<out>/python/<package>/`."""
    inside = os.path.join(package_dir, "qos_files")
    if os.path.isfile(os.path.join(inside, TOPICS_FILE)):
        return inside
    return os.path.normpath(os.path.join(package_dir, os.pardir, os.pardir, "qos"))


class RapidQos:
    """The QoS of each topic, publisher and subscriber, from one generated qos folder:
    `qos_dir`, else `package_dir`'s default (package_qos_dir).

    Attributes from topics.json: asset, domain, partition (None without an asset),
    library, topics (topic names, in file order).
    """

    def __init__(self, qos_dir: str | os.PathLike[str] | None = None, package_dir: str | None = None) -> None:
        given = qos_dir is not None
        if qos_dir is not None:
            self.qos_dir = os.path.abspath(os.fspath(qos_dir))
        elif package_dir is not None:
            self.qos_dir = os.path.abspath(package_qos_dir(package_dir))
        else:
            raise QosFilesMissing("no qos folder: pass it, RapidQos('OUT/qos'), or use a generated package's "
                                  "<package>.qos.RapidQos")
        self.topics_file = os.path.join(self.qos_dir, TOPICS_FILE)
        if not os.path.isfile(self.topics_file):
            where = "" if given else " (the default: the qos folder beside <out>/python/)"
            raise QosFilesMissing(
                f"no {TOPICS_FILE} in {self.qos_dir}{where}: generate with `rapidgen generate ... "
                "--lang python,qos -o OUT`, or pass the qos folder: RapidQos('OUT/qos')")
        try:
            with open(self.topics_file, encoding="utf-8") as fh:
                data = json.load(fh)
            self._keys: dict[str, str] = {entry["topic"]: entry["key"] for entry in data["topics"]}
            self._transports: dict[str, str] = {name: t["cyclonedds"] for name, t in data["transports"].items()}
            self.default_transport: str = data["default_transport"]
            dds_xml = data["files"]["dds_xml"]
        except (ValueError, KeyError, TypeError, AttributeError) as exc:
            raise RapidQosError(f"{self.topics_file} is not a rapidgen topic map ({exc!r})") from None
        self.asset = data.get("asset")
        self.domain = data.get("domain")
        self.partition = data.get("partition")
        self.library = data.get("library")
        self.topics = tuple(self._keys)
        self.dds_xml = self._path(dds_xml)
        # cyclonedds' QosProvider is not thread-safe: two threads asking at once can get
        # each other's profile (seen: a sample writer made TransientLocal)
        self._lock = threading.Lock()
        try:
            self._provider = QosProvider(self.dds_xml)
        except DDSException as exc:
            raise RapidQosError(f"Cyclone's QoS provider cannot load {self.dds_xml}: {exc}") from None

    def _path(self, relative: str) -> str:
        path = os.path.join(self.qos_dir, relative)
        if not os.path.isfile(path):
            raise QosFilesMissing(f"{self.topics_file} names {relative}, which is not in {self.qos_dir}")
        return path

    def key(self, topic: Any) -> str:
        """The topic's profile key, `library::profile`."""
        try:
            return self._keys[topic]
        except (KeyError, TypeError):
            pass
        close = difflib.get_close_matches(str(topic), self.topics, n=1)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        raise UnknownTopic(f"topic {topic!r} is not in {self.topics_file} "
                           f"({len(self.topics)} topics){hint}") from None

    def _group_key(self, topic: str | None) -> str:
        if topic is not None:
            return self.key(topic)
        if not self.topics:
            raise RapidQosError(f"{self.topics_file} lists no topics: name a profile's topic")
        return self._keys[self.topics[0]]

    def _get(self, getter: Callable[[str], Qos], key: str) -> Qos:
        with self._lock:
            return getter(key)

    def writer(self, topic: str) -> Qos:
        """DataWriter QoS of the topic's profile."""
        return self._get(self._provider.get_datawriter_qos, self.key(topic))

    def reader(self, topic: str) -> Qos:
        """DataReader QoS of the topic's profile."""
        return self._get(self._provider.get_datareader_qos, self.key(topic))

    def publisher(self, topic: str | None = None) -> Qos:
        """Publisher QoS (the partition) of the topic's profile, by default of the first topic's."""
        return self._get(self._provider.get_publisher_qos, self._group_key(topic))

    def subscriber(self, topic: str | None = None) -> Qos:
        """Subscriber QoS (the partition) of the topic's profile, by default of the first topic's."""
        return self._get(self._provider.get_subscriber_qos, self._group_key(topic))

    def cyclonedds_config(self, transport: str | None = None) -> str:
        """Absolute path of the Cyclone DDS configuration of a transport (default: topics.json's)."""
        name = self.default_transport if transport is None else transport
        if name not in self._transports:
            raise RapidQosError(f"no transport {name!r} in {self.topics_file} "
                                f"(known: {', '.join(sorted(self._transports))})")
        return self._path(self._transports[name])
