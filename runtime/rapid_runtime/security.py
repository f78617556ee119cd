"""DDS Security on the Python side: a participant joins a secured domain with an enclave of a
`rapidgen secure` keystore, whose cyclonedds-security.xml (Cyclone's <Security> section, the
enclave's files by absolute path) is added to CYCLONEDDS_URI before the participant starts.

The Cyclone DDS under the `cyclonedds` binding must have the security plugins: the PyPI
wheel has none; scripts/setup.sh builds Cyclone 11.0.1 with them and rebuilds the binding
against it (scripts/cyclone_security.sh; docs/security.md, "The Python side").

The bridge takes the C++ runtime's variables (docs/secure.md, "Running secured"):
RAPID_SECURITY_KEYSTORE=DIR, and RAPID_SECURITY_ENCLAVE=NAME (DIR/enclaves/NAME) or a path
with a '/'; the enclave defaults to the asset's name. The tools take --enclave DIR."""
from __future__ import annotations

import importlib.util
import os

SECURITY_FILE = "cyclonedds-security.xml"
PLUGIN = "libdds_security_auth.so"  # one of the three; Cyclone dlopens them beside libddsc


class SecurityUnavailable(RuntimeError):
    """The enclave cannot be used: missing, or this Cyclone has no DDS Security."""


def cyclone_has_security() -> bool:
    """True when the libddsc the binding loads has the security plugins beside it."""
    spec = importlib.util.find_spec("cyclonedds")
    if spec is None or not spec.submodule_search_locations:
        return False
    record = os.path.join(spec.submodule_search_locations[0], "__library__.py")
    try:
        with open(record, encoding="utf-8") as f:
            text = f.read()
    except OSError:
        return False
    # `library_path = r'...'` when built against a Cyclone install (the wheel computes its path)
    for line in text.splitlines():
        if line.startswith("library_path = r'") and line.endswith("'"):
            return os.path.exists(os.path.join(os.path.dirname(line[len("library_path = r'"):-1]), PLUGIN))
    return False


def enclave_from_environment(default_name: str) -> str | None:
    """The enclave RAPID_SECURITY_KEYSTORE and RAPID_SECURITY_ENCLAVE name, or None (unsecured)."""
    keystore = os.environ.get("RAPID_SECURITY_KEYSTORE", "")
    if not keystore:
        return None
    name = os.environ.get("RAPID_SECURITY_ENCLAVE", "") or default_name
    return name if "/" in name else os.path.join(keystore, "enclaves", name)


def use_enclave(enclave: str) -> str:
    """Add the enclave's <Security> section to CYCLONEDDS_URI (after the transport file, which
    must be set first). Must run before the first participant starts. Returns the file."""
    path = os.path.join(os.path.abspath(enclave), SECURITY_FILE)
    if not os.path.isfile(path):
        raise SecurityUnavailable(
            f"{enclave}: no {SECURITY_FILE} in it (an enclave of a `rapidgen secure` keystore has one; "
            "a keystore made before the Python side was secured needs one more run of rapidgen secure)")
    if not cyclone_has_security():
        raise SecurityUnavailable(
            "this cyclonedds binding runs on a Cyclone DDS without DDS Security (the PyPI wheel): "
            "scripts/setup.sh builds one (scripts/cyclone_security.sh VENV)")
    uri = os.environ.get("CYCLONEDDS_URI", "")
    os.environ["CYCLONEDDS_URI"] = ",".join(u for u in (uri, "file://" + path) if u)
    return path
