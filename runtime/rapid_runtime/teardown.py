"""Deleting a cyclonedds participant now, on the caller's thread, not at interpreter exit
(dds.Node.close(), the Commander, the bridge's main(), and the rapidgen tools through
rapidgen/live/teardown.py).

cyclonedds-python (11.0.1) deletes an entity only in Entity.__del__, and only while the
entity's handle is still in the class's WeakValueDictionary of entities. A program's
participant sits in reference cycles (listeners' closures, a reader thread's bound method,
the traceback of a creation DDS refused), and the cyclic collector clears weak references
before it calls finalizers: the handle is gone from the dictionary by the time __del__ runs,
which then deletes nothing. So the C participant and its domain's threads live until the
process ends. When exit() runs the libraries' destructors, OpenSSL's exit handler frees its
locks while a receive thread may still be decoding a peer's secured submessage: SIGSEGV
after the program's last line (`rapidgen conform` refused by DDS Security beside a secured
C++ bridge, about 2 runs in 100 under load; the core: ddsi_recv_thread ->
decode_datawriter_submessage -> HMAC -> CRYPTO_THREAD_read_lock(NULL), the main thread in
exit() -> _dl_fini). Deleting the participant explicitly stops its domain's threads (the
last participant's delete joins them).
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
