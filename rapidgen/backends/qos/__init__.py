"""The `qos` back end: RAPID's QoS library (+ an asset's overrides) as vendor files.

Output, under qos/:
  fastdds/rapid_qos_profiles.xml   Fast DDS 2.9: participant profiles per transport,
                                   data_writer/data_reader profiles per RAPID profile
  cyclonedds/<transport>.xml       Cyclone DDS domain configuration, one per transport
  rti/USER_QOS_PROFILES.xml        RTI Connext, RAPID's original qos_library form
  dds-xml/rapid_qos.xml            OMG DDS-XML 1.0 (Cyclone's QoS provider loads it)
  topics.json                      topic -> type, profile: what the runtimes read

The driver (rapidgen.generate) reads the library, the one the package ships
(specs/qos/rapid.yaml), and passes it in Options: back ends never read files. `render()`
takes any library (tests, sites with their own peers and servers).
"""
from __future__ import annotations

import json

from rapidgen.backends.base import (QOS_LIBRARY, GeneratedFile, GenerationError, Options, check_output,
                                   embed_nothing, no_companions, notice)
from rapidgen.backends.escape import xml_comment as comment_text  # noqa: F401 (kept for callers)
from rapidgen.backends.qos import streams, topicmap, view
from rapidgen.backends.templating import render as render_template
from rapidgen.diagnostics import did_you_mean
from rapidgen.model.ir import Model
from rapidgen.qos.spec import QosSpec

NAME = "qos"

FASTDDS_FILE = "fastdds/rapid_qos_profiles.xml"
DDS_XML_FILE = "dds-xml/rapid_qos.xml"
RTI_FILE = "rti/USER_QOS_PROFILES.xml"
TOPICS_FILE = "topics.json"


class UnknownProfile(GenerationError):
    """Topics whose profile the QoS library lacks (a library without RAPID's profiles)."""

    def __init__(self, spec: QosSpec, entries: list) -> None:
        super().__init__(f"{len(entries)} topics name profiles QoS library {spec.library} lacks")
        self.spec, self.entries = spec, entries

    def report(self, sink) -> None:
        names = [p.name for p in self.spec.profiles]
        for e in self.entries:
            sink.error("RG1608", f"topic '{e.topic}' uses QoS profile '{e.profile}', which library "
                       f"{self.spec.library} ({self.spec.file}) lacks", e.loc, did_you_mean(e.profile, names))


companions, embed = no_companions, embed_nothing


def needs(asset) -> frozenset[str]:
    return frozenset({QOS_LIBRARY})


def cyclone_file(transport: str) -> str:
    return f"cyclonedds/{transport}.xml"


def generate(model: Model, asset, options: Options) -> list[GeneratedFile]:
    """Render the QoS library the driver read (rapidgen.generate); the package's own by default."""
    spec = options.qos_library if isinstance(options.qos_library, QosSpec) else None
    if spec is None:
        raise NoLibrary()
    return render(spec, model, asset, options)


class NoLibrary(GenerationError):
    def report(self, sink) -> None:
        from rapidgen.diagnostics import SourceLoc
        sink.error("RG1609", "the qos target needs a QoS library", SourceLoc("<command line>", 0, 0),
                   "rapidgen generate/check pass the packaged one (specs/qos/rapid.yaml)")


def render(spec: QosSpec, model: Model, asset, options: Options) -> list[GeneratedFile]:
    head = notice(options.source)  # templates escape every value printed in a comment
    asset_name = asset.spec.name if asset is not None else None
    topics = topicmap.from_asset(asset, spec) if asset is not None else topicmap.from_model(model, spec)
    missing = [e for e in topics if not spec.has_profile(e.profile)]
    if missing:
        raise UnknownProfile(spec, missing)
    common = dict(notice=head, library=spec.library, asset=asset_name)
    files = []

    transports, participants = view.fastdds_view(spec, asset)
    files.append(GeneratedFile(FASTDDS_FILE, render_template(
        NAME, "fastdds.xml.j2", transports=transports, participants=participants, streams=streams.profiles(asset),
        links=view.fastdds_links(spec), profiles=view.effective_profiles(spec, asset, view.FASTDDS_NAMES, True), **common)))

    files.append(GeneratedFile(DDS_XML_FILE, render_template(
        NAME, "dds_xml.xml.j2", profiles=view.effective_profiles(spec, asset, view.OMG_NAMES, False), **common)))

    files.append(GeneratedFile(RTI_FILE, render_template(
        NAME, "rti.xml.j2", profiles=view.rti_profiles(spec, asset), transports=view.rti_transports(spec),
        **common)))

    for t in view.cyclone_views(spec):
        files.append(GeneratedFile(cyclone_file(t.name), render_template(NAME, "cyclonedds.xml.j2", t=t, **common)))

    files.append(GeneratedFile(TOPICS_FILE, topics_json(spec, asset, topics, options)))
    check_output(files, asset)
    return files


def topics_json(spec: QosSpec, asset, topics: list[topicmap.TopicEntry], options: Options) -> str:
    default = spec.default_transport.name
    data = {
        "_generated": notice(options.source),
        "library": spec.library,
        "asset": asset.spec.name if asset is not None else None,
        "domain": asset.spec.domain if asset is not None else None,
        "partition": view.partition_of(spec, asset),
        "default_transport": default,
        "transports": {t.name: {"cyclonedds": cyclone_file(t.name),
                                "fastdds_participant": f"rapid_{t.name}",
                                **({"fastdds_tcp_participant": f"rapid_{t.name}_tcp",
                                    "fastdds_discovery_server": f"rapid_{t.name}_tcp_server"} if t.tcp else {}),
                                "rti_profile": f"{spec.library}::{view.rti_transport_name(t)}"}
                       for t in spec.transports},
        "files": {"fastdds": FASTDDS_FILE, "dds_xml": DDS_XML_FILE, "rti": RTI_FILE},
        "topics": [{"topic": e.topic, "type": e.type, "role": e.role, "direction": e.direction,
                    "profile": e.profile, "key": f"{spec.library}::{e.profile}"} for e in topics],
    }
    return json.dumps(data, indent=2, ensure_ascii=False) + "\n"


__all__ = ["NAME", "generate", "render"]
