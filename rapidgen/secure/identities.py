"""What a secured bridge needs from the keystore to bind a command's cmdSrc to the
participant that wrote it (docs/secure.md, "cmdSrc bound to the certificate").

DDS Security's PKI-DH makes a participant's GUID prefix from its identity certificate: the
first bit 1, then the first 47 bits of the SHA-256 of the certificate's subject name (its
DER encoding, OpenSSL's X509_NAME_digest), and Fast DDS 2.9 refuses a handshake whose
participant GUID does not come from the certificate it authenticated with. So a bridge that
knows each ground source's subject digest can tell, from the GUID of the writer a command
came from, whose certificate wrote it.

`rapidgen secure` writes that list into every asset's enclave as `identities.txt`:

    # comment lines
    RapidWorkbench 5f1c...(64 hex digits) CN=RapidWorkbench
    <source> <sha256 of the DER subject name> <the subject, RFC 4514, for people>

one line per ground tool of the deployment (the sources, sorted), from the certificate in
its enclave. The bridge reads only the first two fields."""
from __future__ import annotations

import hashlib
from pathlib import Path

from cryptography import x509

FILE = "identities.txt"
HEADER = ("# rapidgen secure: the ground sources of this deployment and the SHA-256 of their certificate's\n"
          "# subject name (DER). A secured C++ bridge runs a command only when the GUID of the participant\n"
          "# that wrote it comes from the certificate of the source its cmdSrc names (docs/secure.md,\n"
          "# \"cmdSrc bound to the certificate\"). Rewritten by every run; read by the bridge at start.\n")


def subject_digest(cert: x509.Certificate) -> bytes:
    """SHA-256 of the certificate's subject name as DER (what PKI-DH hashes)."""
    return hashlib.sha256(cert.subject.public_bytes()).digest()


def guid_prefix_head(digest: bytes) -> bytes:
    """The first 6 bytes of the GUID prefix a participant with this subject digest gets:
    bit 1, then the digest's first 47 bits (DDS Security 1.1's PKI-DH)."""
    bits = int.from_bytes(digest[:6], "big") >> 1
    return (bits | 1 << 47).to_bytes(6, "big")


def text(certs: dict[str, x509.Certificate]) -> str:
    lines = [f"{name} {subject_digest(cert).hex()} {cert.subject.rfc4514_string()}\n"
             for name, cert in sorted(certs.items())]
    return HEADER + "".join(lines)


def parse(content: str) -> dict[str, str]:
    """source -> subject digest (hex) of an identities.txt."""
    out = {}
    for line in content.splitlines():
        fields = line.split(maxsplit=2)
        if fields and not fields[0].startswith("#") and len(fields) >= 2:
            out[fields[0]] = fields[1]
    return out


def ground_certs(root: Path, sources: list[str]) -> dict[str, x509.Certificate]:
    """The ground tools' certificates, from their enclaves (just written by the run)."""
    return {s: x509.load_pem_x509_certificate((root / "enclaves" / s / "cert.pem").read_bytes()) for s in sources}


def write(root: Path, assets: list[str], sources: list[str]) -> list[str]:
    """Every asset's enclave gets identities.txt for `sources`; returns the enclaves whose
    file changed."""
    from rapidgen.secure import pki
    content = text(ground_certs(root, sources)).encode()
    return [a for a in assets if pki.write_private(root / "enclaves" / a / FILE, content)]


def check(root: Path, assets: list[str], sources: list[str]) -> list[tuple[str, str]]:
    """(file, problem) for each asset's identities.txt that is missing or does not list the
    ground tools' certificates as they are now."""
    try:
        want = parse(text(ground_certs(root, sources)))
    except (OSError, ValueError):
        return []  # (the missing or unusable certificates are reported on their own)
    found = []
    for a in assets:
        rel = f"enclaves/{a}/{FILE}"
        try:
            have = parse((root / rel).read_text(encoding="utf-8"))
        except OSError:
            found.append((rel, "missing: a secured bridge refuses to start without it (run rapidgen secure)"))
            continue
        if have != want:
            found.append((rel, "does not list the ground tools' certificates as they are now (run rapidgen secure)"))
    return found
