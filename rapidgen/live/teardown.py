"""Deleting a cyclonedds participant now, on the caller's thread, not at interpreter exit.

cyclonedds-python deletes an entity only in its __del__. A tool's participant sits in
reference cycles (listeners' closures, a reader thread's bound method, the traceback of a
creation DDS refused), so only the cyclic collector deletes it: at some collection, at
interpreter exit, or not at all. While it lives, Cyclone's threads run; if they still run when
exit() calls the libraries' destructors, a receive thread decoding a peer's secured
submessage calls OpenSSL after OpenSSL's own exit handler freed its locks: SIGSEGV after the
tool's last line (`rapidgen conform` refused by DDS Security, a secured C++ bridge beside it:
the core showed ddsi_recv_thread -> decode_datawriter_submessage -> HMAC ->
CRYPTO_THREAD_read_lock(NULL) while the main thread was in exit() -> _dl_fini). Deleting the
participant first stops its domain's threads (the last participant's delete joins them).
"""
from __future__ import annotations


def delete_participant(dp) -> None:
    """dds_delete the entities of dp this process made (newest first: a condition before its
    reader, a reader before its subscriber), then dp itself. Idempotent, and harmless for an
    entity already gone: Entity.__del__ forgets the handle before deleting it, so the
    collector's later __del__ does nothing."""
    from cyclonedds.core import Entity

    if dp is None or getattr(dp, "_ref", None) not in Entity._entities:
        return
    for e in reversed([e for e in list(Entity._entities.values()) if e is not dp and _of(e, dp)]):
        e.__del__()
    dp.__del__()


def _of(entity, dp) -> bool:
    try:
        return bool(entity._get_participant(entity._ref) == dp._ref)
    except Exception:  # an entity being deleted elsewhere: the participant's delete takes it anyway
        return False
