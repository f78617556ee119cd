"""The keystore `rapidgen secure` creates or brings up to date, laid out like SROS2's:

    KEYSTORE/
      public/identity_ca.cert.pem        the CA that signs participants' certificates
      public/permissions_ca.cert.pem     the CA that signs governance and permissions
      private/identity_ca.key.pem        (the team's own CAs: put their cert and key here first)
      private/permissions_ca.key.pem
      enclaves/governance.xml, governance.p7s
      enclaves/<name>/                   one per asset (its name) and ground tool (its source)
        cert.pem key.pem identity_ca.cert.pem permissions_ca.cert.pem
        governance.p7s permissions.xml permissions.p7s
        cyclonedds-security.xml        the same for Cyclone DDS (its <Security> section)
        identities.txt                 an asset's: the ground sources' subject digests (identities.py)

A participant needs only its enclave folder. Everything is owner-only (0600/0700). A run
keeps what is still right: the CAs, a participant's key and certificate while they are
issued by the identity CA and valid for more than a quarter of their life (`--rotate`
re-issues them all), and a signed file whose XML did not change."""
from __future__ import annotations

import datetime
from dataclasses import dataclass, field
from pathlib import Path

from rapidgen.secure import identities, pki, xmldocs
from rapidgen.secure.deploy import Deployment, partition_of

CAS = ("identity_ca", "permissions_ca")


class KeystoreError(Exception):
    """A keystore that cannot be used as it is (a CA's key that is not its certificate's...)."""


@dataclass
class Outcome:
    created: list[str] = field(default_factory=list)
    updated: list[str] = field(default_factory=list)
    kept: list[str] = field(default_factory=list)
    strangers: list[str] = field(default_factory=list)  # enclaves the deployment does not name
    withdrawn: list[str] = field(default_factory=list)  # what the current signed permissions lose
    new_cas: list[str] = field(default_factory=list)  # CAs replaced by this run (--rotate, a withdrawal)


def enclave(root: Path, name: str) -> Path:
    return root / "enclaves" / name


def _ca(root: Path, which: str, days: int, out: Outcome) -> tuple[pki.Pair, bool]:
    cert, key = root / "public" / f"{which}.cert.pem", root / "private" / f"{which}.key.pem"
    if cert.exists() or key.exists():
        try:
            pair = pki.load_pair(cert, key)
        except (OSError, ValueError) as exc:
            raise KeystoreError(f"{which}: {exc}") from None
        if pair.cert.not_valid_after_utc <= pki.now():
            raise KeystoreError(f"{which} expired on {pair.cert.not_valid_after_utc:%Y-%m-%d}: "
                                "a new CA means new certificates for every participant (move the keystore aside)")
        out.kept.append(which)
        return pair, False
    return _new_ca(root, which, days, out), True


def _new_ca(root: Path, which: str, days: int, out: Outcome) -> pki.Pair:
    """A new CA in place of the keystore's (the old one's key is overwritten). Each has a
    subject of its own (its time of issue): Fast DDS 2.9 compares the permissions CA's
    subject first and logs "Remote participant PermissionsCA differs from local"."""
    cert, key = root / "public" / f"{which}.cert.pem", root / "private" / f"{which}.key.pem"
    replaced = cert.exists()
    pair = pki.make_ca(f"rapidgen {which.replace('_', ' ')} {pki.now():%Y-%m-%dT%H:%M:%SZ}", max(days * 2, 3650))
    pki.write_private(key, pki.key_pem(pair.key))
    pki.write_private(cert, pki.cert_pem(pair.cert))
    if replaced:
        out.updated.append(which)
        out.new_cas.append(which)
        out.kept = [k for k in out.kept if k != which]
    else:
        out.created.append(which)
    return pair


def _identity(folder: Path, name: str, ca: pki.Pair, days: int, rotate: bool, out: Outcome) -> pki.Pair:
    cert_file, key_file = folder / "cert.pem", folder / "key.pem"
    if not rotate and cert_file.exists():
        try:
            pair = pki.load_pair(cert_file, key_file)
        except (OSError, ValueError):
            pair = None
        if pair is not None and pki.issued_by(pair.cert, ca.cert) and pair.cert.subject == pki.subject(name):
            life = pair.cert.not_valid_after_utc - pair.cert.not_valid_before_utc
            if pair.cert.not_valid_after_utc - pki.now() > life / 4:
                out.kept.append(f"{name}/cert.pem")
                return pair
    (out.updated if cert_file.exists() else out.created).append(f"{name}/cert.pem")
    start = pki.now() - datetime.timedelta(minutes=5)
    pair = pki.issue(ca, name, start, start + datetime.timedelta(days=days))
    pki.write_private(key_file, pki.key_pem(pair.key))
    pki.write_private(cert_file, pki.cert_pem(pair.cert))
    return pair


def _signed(xml_file: Path, data: bytes, signer: pki.Pair, resign: bool, out: Outcome, label: str) -> None:
    """`data` in xml_file and signed beside it (.p7s): signed again when the XML changed, the
    CA is new, or the .p7s on disk is not the CA's signature of exactly this XML (a stale
    or foreign one put back, an edited one)."""
    p7s = xml_file.with_suffix(".p7s")
    changed = pki.write_private(xml_file, data)
    if changed or resign or not p7s.exists() or pki.smime_content(p7s.read_bytes(), signer.cert) != data:
        pki.write_private(p7s, pki.sign_smime(data, signer))
        out.updated.append(label)
    else:
        out.kept.append(label)


def grants(dep: Deployment, name: str) -> tuple[xmldocs.Rule, ...]:
    """What participant `name` may publish and read (docs in xmldocs)."""
    C = xmldocs.Criterion
    if name in dep.assets:
        a = dep.assets[name]
        part = partition_of(a)
        # setpoint streams (docs/realtime.md), as the runtime opens them: an output stream is
        # written in the asset's own partition, an input stream read in its source's
        writes: dict[str, set[str]] = {part: {p.topic for p in a.publications}}
        reads: dict[str, set[str]] = {part: {a.command_topic}} if a.command_topic else {}
        for s in a.streams:
            (writes if s.direction == "output" else reads).setdefault(s.partition, set()).add(s.topic)
        return (xmldocs.Rule(dep.domains_of(a), tuple(C(tuple(sorted(t)), (p,)) for p, t in sorted(writes.items())),
                             tuple(C(tuple(sorted(t)), (p,)) for p, t in sorted(reads.items()))),)
    tool = next(t for t in dep.tools if t.source == name)
    by_domains: dict[tuple[int, ...], list[str]] = {}
    for asset in tool.watch:
        by_domains.setdefault(dep.domains_of(dep.assets[asset]), []).append(asset)
    rules = []
    for domains, assets in sorted(by_domains.items()):
        commands: dict[str, list[str]] = {}
        for asset in assets:
            a = dep.assets[asset]
            if asset in tool.command and a.command_topic:
                commands.setdefault(a.command_topic, []).append(partition_of(a))
        pub = tuple(C((topic,), tuple(sorted(parts))) for topic, parts in sorted(commands.items()))
        sub = tuple(C(tuple(sorted({p.topic for p in dep.assets[a].publications} |
                                   ({dep.assets[a].command_topic or ""} if a in tool.audit else set()))),
                      (partition_of(dep.assets[a]),)) for a in assets)
        rules.append(xmldocs.Rule(domains, pub, sub))
    return tuple(rules)


def build(dep: Deployment, root: Path, rotate: bool = False) -> Outcome:
    out = Outcome()
    pki.make_dirs(root)
    for sub in ("public", "private", "enclaves"):
        pki.make_dirs(root / sub)
    identity_ca, new_identity = _ca(root, "identity_ca", dep.validity_days, out)
    permissions_ca, new_permissions = _ca(root, "permissions_ca", dep.validity_days, out)
    if rotate and not new_identity:  # a new trust generation: every enclave handed out before fails
        identity_ca, new_identity = _new_ca(root, "identity_ca", dep.validity_days, out), True
    out.withdrawn = [] if new_permissions else withdrawals(root, dep, permissions_ca.cert)
    if (rotate or out.withdrawn) and not new_permissions:
        # Fast DDS 2.9 honours any permissions its permissions CA signed while their <validity>
        # lasts (it reads no revocation of them): only a new CA cuts off the old ones
        permissions_ca, new_permissions = _new_ca(root, "permissions_ca", dep.validity_days, out), True
    gov = xmldocs.governance()
    _signed(root / "enclaves" / "governance.xml", gov, permissions_ca, new_permissions, out, "governance")
    gov_p7s = (root / "enclaves" / "governance.p7s").read_bytes()
    for name in dep.names():
        folder = enclave(root, name)
        pki.make_dirs(folder)
        pair = _identity(folder, name, identity_ca, dep.validity_days, rotate or new_identity, out)
        pki.write_private(folder / "identity_ca.cert.pem", pki.cert_pem(identity_ca.cert))
        pki.write_private(folder / "permissions_ca.cert.pem", pki.cert_pem(permissions_ca.cert))
        pki.write_private(folder / "governance.p7s", gov_p7s)
        pki.write_private(folder / "cyclonedds-security.xml", xmldocs.cyclone_security(str(folder.resolve())))
        grant = xmldocs.Grant(name, grants(dep, name), pair.cert.not_valid_before_utc, pair.cert.not_valid_after_utc)
        _signed(folder / "permissions.xml", xmldocs.permissions(grant), permissions_ca, new_permissions, out,
                f"{name}/permissions")
    identities.write(root, list(dep.assets), [t.source for t in dep.tools])  # cmdSrc's binding
    known = set(dep.names())
    out.strangers = sorted(p.name for p in (root / "enclaves").iterdir() if p.is_dir() and p.name not in known)
    return out


def _participant_grants(dep: Deployment, name: str) -> dict[str, set[tuple[str, str, str]]]:
    dummy = pki.now()
    return xmldocs.read_grants(xmldocs.permissions(xmldocs.Grant(name, grants(dep, name), dummy, dummy)))


def withdrawals(root: Path, dep: Deployment, permissions_ca) -> list[str]:
    """What the permissions the current permissions CA signed (each enclave's permissions.p7s
    that verifies with it) grant and this run would not: a participant no longer in the
    deployment, or a topic, partition or domain taken from one. Each entry names the
    participant and what it loses."""
    out: list[str] = []
    folders = sorted(p for p in (root / "enclaves").iterdir() if p.is_dir()) if (root / "enclaves").is_dir() else []
    known = set(dep.names())
    for folder in folders:
        try:
            content = pki.smime_content((folder / "permissions.p7s").read_bytes(), permissions_ca)
        except OSError:
            continue
        if content is None:
            continue  # another CA's: already refused by every participant that has the current one
        try:
            had = xmldocs.read_grants(content)
        except (ValueError, SyntaxError):  # signed, but not XML this module reads: withdrawn as a whole
            out.append(f"{folder.name} (permissions it cannot read)")
            continue
        if folder.name not in known:
            out.append(f"{folder.name} (no longer in the deployment)")
            continue
        now = _participant_grants(dep, folder.name)
        lost = [f"{kind} {t} in {p} on domain {d}" for kind in ("publish", "subscribe")
                for d, t, p in sorted(had.get(kind, set()) - now[kind])]
        if lost:
            out.append(f"{folder.name} ({'; '.join(lost[:3])}{'; ...' if len(lost) > 3 else ''})")
    return out


@dataclass(frozen=True)
class Finding:
    severity: str  # "error" | "warning"
    file: str  # relative to the keystore
    message: str


def _check_signed(root: Path, signed: str, xml: str, ca) -> list[Finding]:
    """A signed document against the CA and the XML it should carry (both must hold: Fast DDS
    reads the signed file, and takes any the CA signed while its validity lasts)."""
    try:
        data = (root / signed).read_bytes()
        want = (root / xml).read_bytes()
    except OSError:
        return []  # reported as missing
    content = pki.smime_content(data, ca)
    if content is None:
        return [Finding("error", signed, "not signed by public/permissions_ca.cert.pem (another CA's, or altered): "
                        "run rapidgen secure")]
    if content != want:
        return [Finding("error", signed, f"signed by the CA but not what {xml} says (a stale one put back?): "
                        "run rapidgen secure")]
    return []


def check(root: Path, dep: Deployment | None, warn_days: int) -> list[Finding]:
    """Expired or soon-expiring certificates and grants, a participant's certificate not from
    the identity CA, missing files, every signed document (governance.p7s, permissions.p7s)
    that the permissions CA did not sign or that does not carry its XML, an enclave's CA
    copies that are not the keystore's, and (with the deployment) permissions that are not
    what the deployment and descriptors say."""
    found: list[Finding] = []
    now = pki.now()
    soon = now + datetime.timedelta(days=warn_days)

    def dates(rel: str, cert) -> None:
        end = cert.not_valid_after_utc
        if end <= now:
            found.append(Finding("error", rel, f"expired on {end:%Y-%m-%d %H:%M} UTC"))
        elif end <= soon:
            found.append(Finding("warning", rel, f"expires on {end:%Y-%m-%d %H:%M} UTC, in {(end - now).days} days"))

    cas = {}
    for which in CAS:
        rel = f"public/{which}.cert.pem"
        try:
            cas[which] = pki.load_pair(root / rel, root / "private" / f"{which}.key.pem").cert
        except (OSError, ValueError) as exc:
            found.append(Finding("error", rel, f"unusable: {getattr(exc, 'strerror', None) or exc}"))
            continue
        dates(rel, cas[which])
    names = dep.names() if dep else sorted(p.name for p in (root / "enclaves").iterdir() if p.is_dir()) \
        if (root / "enclaves").is_dir() else []
    if "permissions_ca" in cas:
        found += _check_signed(root, "enclaves/governance.p7s", "enclaves/governance.xml", cas["permissions_ca"])
        gov = root / "enclaves" / "governance.xml"
        if gov.is_file() and gov.read_bytes() != xmldocs.governance():
            found.append(Finding("error", "enclaves/governance.xml",
                                 "not the governance rapidgen writes (edited?): run rapidgen secure"))
    for name in names:
        folder = enclave(root, name)
        for f in ("cert.pem", "key.pem", "identity_ca.cert.pem", "permissions_ca.cert.pem", "governance.p7s",
                  "permissions.xml", "permissions.p7s"):
            if not (folder / f).is_file():
                found.append(Finding("error", f"enclaves/{name}/{f}", "missing (run rapidgen secure)"))
        try:
            pair = pki.load_pair(folder / "cert.pem", folder / "key.pem")
        except (OSError, ValueError):
            continue
        dates(f"enclaves/{name}/cert.pem", pair.cert)
        if "identity_ca" in cas and not pki.issued_by(pair.cert, cas["identity_ca"]):
            found.append(Finding("error", f"enclaves/{name}/cert.pem", "not issued by public/identity_ca.cert.pem"))
        if dep is not None and (folder / "permissions.xml").is_file():
            want = xmldocs.permissions(xmldocs.Grant(name, grants(dep, name), pair.cert.not_valid_before_utc,
                                                     pair.cert.not_valid_after_utc))
            if (folder / "permissions.xml").read_bytes() != want:
                found.append(Finding("error", f"enclaves/{name}/permissions.xml",
                                     "not what the deployment and descriptors grant now (run rapidgen secure)"))
        for ca in CAS:  # the enclave's copies: what its participant trusts
            copy = folder / f"{ca}.cert.pem"
            if ca in cas and copy.is_file() and copy.read_bytes() != pki.cert_pem(cas[ca]):
                found.append(Finding("error", f"enclaves/{name}/{ca}.cert.pem",
                                     f"not public/{ca}.cert.pem (an enclave from before a new CA: run rapidgen secure "
                                     "and hand it out)"))
        if "permissions_ca" in cas:
            found += _check_signed(root, f"enclaves/{name}/permissions.p7s", f"enclaves/{name}/permissions.xml",
                                   cas["permissions_ca"])
            found += _check_signed(root, f"enclaves/{name}/governance.p7s", "enclaves/governance.xml",
                                   cas["permissions_ca"])
    if dep is not None:
        sources = [t.source for t in dep.tools]
        found += [Finding("error", f, m) for f, m in identities.check(root, list(dep.assets), sources)]
    return found
