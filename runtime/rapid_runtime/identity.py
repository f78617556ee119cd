"""cmdSrc bound to the certificate (docs/secure.md): a secured bridge runs a command only
when its cmdSrc names the ground source whose certificate authenticated the participant
that wrote it. DDS Security's PKI-DH makes a participant's GUID prefix from its identity
certificate (bit 1, then the first 47 bits of the SHA-256 of its subject name), and
`rapidgen secure` writes each ground source's subject digest into the asset's enclave
(identities.txt), so the writer's GUID tells whose certificate wrote a command. The C++
runtime's identity.cpp does the same; the refusal's text is the same."""
from __future__ import annotations

import os

from rapid_runtime.untrusted import visible

FILE = "identities.txt"


class IdentitiesError(RuntimeError):
    """identities.txt missing or malformed: a secured bridge does not start without it."""


def comes_from(prefix: bytes, digest: bytes) -> bool:
    """True when a GUID prefix was made from this subject digest: its bits 1..47 are the
    digest's bits 0..46 (bit 0 of the prefix set)."""
    if len(prefix) < 6 or len(digest) < 6 or not prefix[0] & 0x80:
        return False
    head = int.from_bytes(prefix[:6], "big") & ((1 << 47) - 1)
    return head == int.from_bytes(digest[:6], "big") >> 1


class Identities:
    def __init__(self, sources: dict[str, bytes]):
        self.sources = sources  # source name -> subject digest

    @classmethod
    def parse(cls, text: str, where: str) -> Identities:
        sources: dict[str, bytes] = {}
        for number, line in enumerate(text.splitlines(), 1):
            fields = line.split(maxsplit=2)
            if not fields or fields[0].startswith("#"):
                continue
            try:
                digest = bytes.fromhex(fields[1]) if len(fields) > 1 else b""
            except ValueError:
                digest = b""
            if len(digest) != 32:
                raise IdentitiesError(f"{where}:{number}: expected '<source> <64 hex digits>' (run rapidgen secure)")
            if fields[0] in sources:
                raise IdentitiesError(f"{where}:{number}: source '{visible(fields[0])}' listed twice")
            sources[fields[0]] = digest
        return cls(sources)

    @classmethod
    def load(cls, enclave: str) -> Identities:
        path = os.path.join(enclave, FILE)
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except (OSError, UnicodeDecodeError):
            raise IdentitiesError(f"cannot read {path}: a secured bridge binds cmdSrc to the writer's certificate "
                                  "with it (run rapidgen secure to write it; docs/secure.md)") from None
        return cls.parse(text, path)

    def owner(self, prefix: bytes) -> str:
        return next((name for name, digest in self.sources.items() if comes_from(prefix, digest)), "")

    def refusal(self, cmd_src: str, prefix: bytes) -> str | None:
        """None when the writer's certificate is cmd_src's, else the answer's message."""
        who = self.owner(prefix)
        if who and who == cmd_src:
            return None
        text = f"cmdSrc '{visible(cmd_src, 64)}' is not the writer's identity"
        return text + (f" '{who}'" if who else " (its certificate is none of this keystore's ground sources)")
