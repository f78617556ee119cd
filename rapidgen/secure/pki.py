"""Keys, certificates and S/MIME signatures for the keystore, with `cryptography`.

ECDSA P-256 with SHA-256 everywhere (what SROS2 makes and what the DDS Security builtin
PKI-DH plugins of Fast DDS and Cyclone accept). Every file is written owner-only (0600,
folders 0700) by a rename, so a reader never sees half a key."""
from __future__ import annotations

import base64
import datetime
import hashlib
import os
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

from cryptography import x509
from cryptography.exceptions import InvalidSignature
from cryptography.hazmat.primitives import hashes, serialization
from cryptography.hazmat.primitives.asymmetric import ec
from cryptography.hazmat.primitives.asymmetric.utils import Prehashed
from cryptography.hazmat.primitives.serialization import pkcs7
from cryptography.x509.oid import NameOID

UTC = datetime.timezone.utc


@dataclass(frozen=True)
class Pair:
    cert: x509.Certificate
    key: ec.EllipticCurvePrivateKey


def now() -> datetime.datetime:
    return datetime.datetime.now(UTC).replace(microsecond=0)


def subject(common_name: str) -> x509.Name:
    return x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, common_name)])


def make_ca(common_name: str, days: int) -> Pair:
    key = ec.generate_private_key(ec.SECP256R1())
    start = now() - datetime.timedelta(minutes=5)  # a little slack for clocks that differ
    cert = (x509.CertificateBuilder().subject_name(subject(common_name)).issuer_name(subject(common_name))
            .public_key(key.public_key()).serial_number(x509.random_serial_number())
            .not_valid_before(start).not_valid_after(start + datetime.timedelta(days=days))
            .add_extension(x509.BasicConstraints(ca=True, path_length=0), critical=True)
            .add_extension(x509.KeyUsage(digital_signature=True, content_commitment=False, key_encipherment=False,
                                         data_encipherment=False, key_agreement=False, key_cert_sign=True,
                                         crl_sign=True, encipher_only=False, decipher_only=False), critical=True)
            .add_extension(x509.SubjectKeyIdentifier.from_public_key(key.public_key()), critical=False)
            .sign(key, hashes.SHA256()))
    return Pair(cert, key)


def issue(ca: Pair, common_name: str, not_before: datetime.datetime, not_after: datetime.datetime) -> Pair:
    """A participant's new key and its certificate from `ca`."""
    key = ec.generate_private_key(ec.SECP256R1())
    cert = (x509.CertificateBuilder().subject_name(subject(common_name)).issuer_name(ca.cert.subject)
            .public_key(key.public_key()).serial_number(x509.random_serial_number())
            .not_valid_before(not_before).not_valid_after(not_after)
            .add_extension(x509.BasicConstraints(ca=False, path_length=None), critical=True)
            .add_extension(x509.AuthorityKeyIdentifier.from_issuer_public_key(ca.key.public_key()), critical=False)
            .sign(ca.key, hashes.SHA256()))
    return Pair(cert, key)


def issued_by(cert: x509.Certificate, ca: x509.Certificate) -> bool:
    try:
        cert.verify_directly_issued_by(ca)
        return True
    except (ValueError, TypeError, InvalidSignature):
        return False


def sign_smime(data: bytes, signer: Pair) -> bytes:
    """`data` signed as the DDS Security plugins read it: S/MIME, detached, text (as SROS2)."""
    return (pkcs7.PKCS7SignatureBuilder().set_data(data).add_signer(signer.cert, signer.key, hashes.SHA256())
            .sign(serialization.Encoding.SMIME, [pkcs7.PKCS7Options.DetachedSignature, pkcs7.PKCS7Options.Text]))


_MESSAGE_DIGEST = bytes.fromhex("06092a864886f70d010904")  # OID 1.2.840.113549.1.9.4, DER
_TEXT_HEADER = b"Content-Type: text/plain\r\n\r\n"


def _tlv(der: bytes, at: int) -> tuple[int, int, int]:
    """The DER element at `at`: (tag, start of its value, end of its value)."""
    tag, n = der[at], der[at + 1]
    at += 2
    if n & 0x80:
        width = n & 0x7F
        if not 1 <= width <= 4:
            raise ValueError("DER length")
        n = int.from_bytes(der[at:at + width], "big")
        at += width
    if at + n > len(der):
        raise ValueError("DER truncated")
    return tag, at, at + n


def _children(der: bytes, start: int, end: int) -> list[tuple[int, int, int, int]]:
    """The elements inside [start, end): (tag, element start, value start, value end)."""
    out = []
    while start < end:
        tag, v0, v1 = _tlv(der, start)
        out.append((tag, start, v0, v1))
        start = v1
    return out


def smime_content(signed: bytes, ca: x509.Certificate) -> bytes | None:
    """The document a detached, text S/MIME file (sign_smime's, SROS2's) carries when its
    signature verifies with `ca`'s key, as the DDS Security plugins read it (the text/plain
    header dropped, CRLF as LF); None when it is not signed by that key, was altered, or is
    not such a file. What OpenSSL's PKCS7_verify checks for a file signed by the CA itself:
    the signed attributes' message digest is the SHA-256 of the content as sent, and the
    signature over those attributes verifies with the CA's public key."""
    try:
        m = re.search(rb'boundary="([^"]+)"', signed)
        if m is None:
            return None
        delim = b"\r\n--" + m.group(1)
        start = signed.index(b"--" + m.group(1) + b"\r\n") + len(m.group(1)) + 4
        end = signed.index(delim, start)
        part = signed[start:end]
        sig_start = end + len(delim) + 2
        sig_part = signed[sig_start:signed.index(delim, sig_start)]
        der = base64.b64decode(sig_part.split(b"\r\n\r\n", 1)[1], validate=False)
        _, c0, c1 = _tlv(der, 0)  # ContentInfo
        info = _children(der, c0, c1)
        _, sd0, sd1 = _tlv(der, info[1][2])  # [0] EXPLICIT SignedData
        signer_infos = _children(der, sd0, sd1)[-1]
        if signer_infos[0] != 0x31:
            return None
        ok = False
        for _, _, si0, si1 in _children(der, signer_infos[2], signer_infos[3]):
            fields = _children(der, si0, si1)
            attrs = next((f for f in fields if f[0] == 0xA0), None)
            sig = fields[-1]
            if attrs is None or sig[0] != 0x04:
                continue
            digest = None
            for _, _, a0, a1 in _children(der, attrs[2], attrs[3]):
                oid, values = _children(der, a0, a1)[:2]
                if der[oid[1]:oid[3]] == _MESSAGE_DIGEST:
                    value = _children(der, values[2], values[3])[0]
                    digest = der[value[2]:value[3]]
            if digest != hashlib.sha256(part).digest():
                continue
            to_verify = b"\x31" + der[attrs[1] + 1:attrs[3]]  # [0] IMPLICIT re-tagged as the SET signed
            key = ca.public_key()
            if not isinstance(key, ec.EllipticCurvePublicKey):
                return None
            try:
                key.verify(der[sig[2]:sig[3]], hashlib.sha256(to_verify).digest(), ec.ECDSA(Prehashed(hashes.SHA256())))
                ok = True
                break
            except InvalidSignature:
                continue
        if not ok or not part.startswith(_TEXT_HEADER):
            return None
        return part[len(_TEXT_HEADER):].replace(b"\r\n", b"\n")
    except (ValueError, IndexError):
        return None


def cert_pem(cert: x509.Certificate) -> bytes:
    return cert.public_bytes(serialization.Encoding.PEM)


def key_pem(key: ec.EllipticCurvePrivateKey) -> bytes:
    return key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                             serialization.NoEncryption())


def load_pair(cert_file: Path, key_file: Path) -> Pair:
    """A certificate and its key; ValueError when they do not belong together (or are not P-256 ECDSA)."""
    cert = x509.load_pem_x509_certificate(cert_file.read_bytes())
    key = serialization.load_pem_private_key(key_file.read_bytes(), password=None)
    if not isinstance(key, ec.EllipticCurvePrivateKey):
        raise ValueError(f"{key_file.name} is not an ECDSA key")
    if key.public_key().public_numbers() != cert.public_key().public_numbers():  # type: ignore[union-attr]
        raise ValueError(f"{key_file.name} is not the key of {cert_file.name}")
    return Pair(cert, key)


def make_dirs(path: Path) -> None:
    path.mkdir(mode=0o700, parents=True, exist_ok=True)
    os.chmod(path, 0o700)


def write_private(path: Path, data: bytes) -> bool:
    """Write `data` owner-only (0600) unless the file already holds it; True when written."""
    try:
        if path.read_bytes() == data:
            os.chmod(path, 0o600)
            return False
    except OSError:
        pass
    make_dirs(path.parent)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")  # mkstemp: mode 0600
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise
    return True
