"""cyclonedds, imported only when a live command runs, and the transport choice."""
from __future__ import annotations

import importlib
import os
import sys

TRANSPORTS = ("local", "lan", "wan")


class DdsUnavailable(RuntimeError):
    """cyclonedds is not installed: live commands cannot run."""


def require_cyclonedds():
    """The cyclonedds module, or DdsUnavailable with how to get it."""
    try:
        return importlib.import_module("cyclonedds")
    except ImportError as exc:
        raise DdsUnavailable(
            f"this command talks DDS and needs the cyclonedds package ({exc}); "
            "install it with: pip install 'rapidgen[dds]'") from None


def dds_missing(tool: str) -> bool:
    """True (said on stderr, the tool then exits 1) when cyclonedds is not installed."""
    try:
        require_cyclonedds()
    except DdsUnavailable as exc:
        print(f"rapidgen {tool}: {exc}", file=sys.stderr)
        return True
    return False


def add_enclave_argument(p) -> None:
    p.add_argument("--enclave", metavar="DIR", help="join a secured domain as this enclave of a `rapidgen secure` "
                   "keystore (KEYSTORE/enclaves/NAME: its certificate and grants; docs/secure.md)")


def use_transport(config_path: str, keep_environment: bool, enclave: str | None = None) -> str:
    """Point CYCLONEDDS_URI at a generated transport file before the first participant
    starts (Cyclone reads it then). With keep_environment, a CYCLONEDDS_URI already set
    (e.g. a test's loopback file) wins. An enclave's <Security> section goes after it; one
    that cannot be used ends the tool (exit 1, saying why). Returns the URI in use."""
    from rapidgen.live.cyclone_log import quiet_warnings
    quiet_warnings()  # a C++ bridge's retired acks: a Cyclone warning each (cyclone_log.py)
    if not (keep_environment and os.environ.get("CYCLONEDDS_URI")):
        os.environ["CYCLONEDDS_URI"] = "file://" + os.path.abspath(config_path)
    if enclave:
        use_enclave(enclave)
    return os.environ["CYCLONEDDS_URI"]


def use_enclave(enclave: str) -> None:
    """The runtime's use_enclave, its refusal said on stderr and the tool ended (exit 1)."""
    from rapid_runtime.security import SecurityUnavailable
    from rapid_runtime.security import use_enclave as add
    try:
        add(enclave)
    except SecurityUnavailable as exc:
        print(f"rapidgen: --enclave: {exc}", file=sys.stderr)
        raise SystemExit(1) from None


def security_refusal(tool: str, needs: str, enclave: str | None, exc: Exception, does: str, grant: str) -> str | None:
    """The line a live tool prints when DDS Security refused it an entity with `enclave`
    (cyclonedds' DDSException names the refusal NOT_ALLOWED_BY_SECURITY), else None: the
    exception is not a refusal and goes on."""
    from rapidgen.textsafe import visible

    if not enclave or "SECURITY" not in str(exc):
        return None
    return (f"rapidgen {tool}: DDS Security refused what the {needs} needs with the enclave {visible(enclave)} "
            f"({does}: the deployment must grant its source {grant} on the asset; docs/secure.md): "
            f"{visible(str(exc))}")
