"""governance.xml and permissions.xml (OMG DDS-Security 1.1, builtin Access-Permissions
plugin), written with xml.etree: every name escaped, the same bytes for the same input.

The rules (docs/security.md, "DDS Security"):
- governance: no unauthenticated participant, join access control, discovery and liveliness
  encrypted, RTPS messages signed, and every topic with read and write access control,
  metadata and data encrypted (AES-GCM);
- an asset publishes its publications (configs, telemetry, acks, states) and subscribes to
  its command topic, in its own partition only;
- a ground tool publishes commands only in the partitions of the assets it may command and
  reads the publications of those it commands or watches, each in its partition; one that
  audits an asset (rapidgen conform, a recorder) also reads its command topic.
Anything not granted is denied (<default>DENY</default>).
"""
from __future__ import annotations

import datetime
import xml.etree.ElementTree as ET
from dataclasses import dataclass

GOV_XSD = "http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd"
PERM_XSD = "http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd"
XSI = "http://www.w3.org/2001/XMLSchema-instance"
MAX_DOMAIN = 230  # Cyclone's Access-Permissions parser refuses larger ids (Fast DDS takes 232)


@dataclass(frozen=True)
class Criterion:
    """One <publish> or <subscribe>: topics in partitions."""
    topics: tuple[str, ...]
    partitions: tuple[str, ...]


@dataclass(frozen=True)
class Rule:
    """One <allow_rule>: what a participant may do on some domains."""
    domains: tuple[int, ...]
    publish: tuple[Criterion, ...]
    subscribe: tuple[Criterion, ...]


@dataclass(frozen=True)
class Grant:
    name: str  # the participant's certificate CN
    rules: tuple[Rule, ...]
    not_before: datetime.datetime
    not_after: datetime.datetime


def _sub(parent: ET.Element, tag: str, text: str | None = None) -> ET.Element:
    el = ET.SubElement(parent, tag)
    if text is not None:
        el.text = text
    return el


def _root() -> ET.Element:
    return ET.Element("dds", {"xmlns:xsi": XSI})


def _bytes(root: ET.Element, xsd: str) -> bytes:
    root.set("xsi:noNamespaceSchemaLocation", xsd)
    ET.indent(root, "  ")
    return b'<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="utf-8",
                                                                      xml_declaration=False) + b"\n"


def governance() -> bytes:
    root = _root()
    dom_rule = _sub(_sub(root, "domain_access_rules"), "domain_rule")
    rng = _sub(_sub(dom_rule, "domains"), "id_range")
    _sub(rng, "min", "0")
    _sub(rng, "max", str(MAX_DOMAIN))
    for tag, value in (("allow_unauthenticated_participants", "false"), ("enable_join_access_control", "true"),
                       ("discovery_protection_kind", "ENCRYPT"), ("liveliness_protection_kind", "ENCRYPT"),
                       ("rtps_protection_kind", "SIGN")):
        _sub(dom_rule, tag, value)
    topic = _sub(_sub(dom_rule, "topic_access_rules"), "topic_rule")
    for tag, value in (("topic_expression", "*"), ("enable_discovery_protection", "true"),
                       ("enable_liveliness_protection", "true"), ("enable_read_access_control", "true"),
                       ("enable_write_access_control", "true"), ("metadata_protection_kind", "ENCRYPT"),
                       ("data_protection_kind", "ENCRYPT")):
        _sub(topic, tag, value)
    return _bytes(root, GOV_XSD)


def _time(t: datetime.datetime) -> str:
    return t.astimezone(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%S")


def _criterion(parent: ET.Element, tag: str, c: Criterion) -> None:
    el = _sub(parent, tag)
    topics = _sub(el, "topics")
    for t in c.topics:
        _sub(topics, "topic", t)
    parts = _sub(el, "partitions")
    for p in c.partitions:
        _sub(parts, "partition", p)


def permissions(grant: Grant) -> bytes:
    root = _root()
    g = _sub(_sub(root, "permissions"), "grant", None)
    g.set("name", grant.name)
    _sub(g, "subject_name", f"CN={grant.name}")
    validity = _sub(g, "validity")
    _sub(validity, "not_before", _time(grant.not_before))
    _sub(validity, "not_after", _time(grant.not_after))
    for r in grant.rules:
        rule = _sub(g, "allow_rule")
        doms = _sub(rule, "domains")
        for d in r.domains:
            _sub(doms, "id", str(d))
        for c in r.publish:
            _criterion(rule, "publish", c)
        for c in r.subscribe:
            _criterion(rule, "subscribe", c)
    _sub(g, "default", "DENY")
    return _bytes(root, PERM_XSD)


def read_grants(data: bytes) -> dict[str, set[tuple[str, str, str]]]:
    """What a permissions.xml grants: {"publish"/"subscribe": {(domain, topic, partition)}}
    (for tests and --check; reads only what `permissions` writes)."""
    root = ET.fromstring(data)
    out: dict[str, set[tuple[str, str, str]]] = {"publish": set(), "subscribe": set()}
    for rule in root.iter("allow_rule"):
        doms = [e.text or "" for e in rule.iter("id")]
        for kind in ("publish", "subscribe"):
            for c in rule.findall(kind):
                for d in doms:
                    for t in c.iter("topic"):
                        for p in c.iter("partition"):
                            out[kind].add((d, t.text or "", p.text or ""))
    return out


def cyclone_security(enclave: str) -> bytes:
    """Cyclone DDS's <Security> section for an enclave (absolute folder): a Python tool or
    bridge on a Cyclone built with security adds it to CYCLONEDDS_URI (docs/secure.md)."""
    root = ET.Element("CycloneDDS", {"xmlns": "https://cdds.io/config"})
    sec = _sub(_sub(root, "Domain", None), "Security")
    root[0].set("Id", "any")
    for part, lib, init, items in (
            ("Authentication", "dds_security_auth", "authentication",
             (("IdentityCA", "identity_ca.cert.pem"), ("IdentityCertificate", "cert.pem"), ("PrivateKey", "key.pem"))),
            ("AccessControl", "dds_security_ac", "access_control",
             (("PermissionsCA", "permissions_ca.cert.pem"), ("Governance", "governance.p7s"),
              ("Permissions", "permissions.p7s"))),
            ("Cryptographic", "dds_security_crypto", "crypto", ())):
        el = _sub(sec, part)
        if part == "Authentication":  # hash_c1 and hash_c2 in the handshake: Fast DDS 2.9 requires them
            _sub(el, "IncludeOptionalFields", "true")
        _sub(el, "Library").attrib.update({"path": lib, "initFunction": f"init_{init}",
                                           "finalizeFunction": f"finalize_{init}"})
        for tag, name in items:
            _sub(el, tag, f"file:{enclave}/{name}")
    ET.indent(root, "  ")
    return b'<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="utf-8") + b"\n"
