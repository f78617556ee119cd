"""What the generated types modules call (each package's `_support` names these): an
annotation for long bounded sequences, and decoding that fails with one error type.
Written once here instead of in every package (docs/python-backend.md)."""
from __future__ import annotations

import struct
import typing
from typing import Any, TypeVar

import cyclonedds.idl.types as types


def sequence(subtype: Any, bound: int) -> Any:
    """The annotation `types.sequence[subtype, bound]`, for any bound.

    cyclonedds 11.0.1's subscript form refuses bounds above 65535 (it returns an error
    object instead of the annotation); this builds the same annotation directly.
    """
    return typing.Annotated[typing.Sequence[subtype], types.sequence(subtype, bound)]


class DeserializeError(ValueError):
    """Bytes that are not a valid encoding of the type: truncated or overlong data, a length
    or discriminator out of range, text that is not UTF-8, an unknown enumerator."""


# What cyclonedds 11's decoder raises on bad bytes (struct.error: data too short;
# UnicodeDecodeError and ValueError: bad text or enumerator; the others: bad lengths/cases).
_BAD_BYTES = (struct.error, ValueError, IndexError, KeyError, OverflowError)


_Cls = TypeVar("_Cls", bound=type)


def checked(cls: _Cls) -> _Cls:
    """Class decorator: cls.deserialize and cls.deserialize_key raise DeserializeError, and
    only that, for bad bytes; what they return for good bytes is unchanged."""
    for name in ("deserialize", "deserialize_key"):
        plain = getattr(cls, name).__func__

        def guarded(klass, data, *args, _plain=plain, _name=name, **kwargs):
            try:
                return _plain(klass, data, *args, **kwargs)
            except _BAD_BYTES as exc:
                raise DeserializeError(f"{klass.__name__}.{_name}: not a valid encoding "
                                       f"({type(exc).__name__}: {exc})") from exc

        guarded.__name__ = guarded.__qualname__ = name
        guarded.__doc__ = f"cyclonedds' {name}; bad bytes raise DeserializeError."
        setattr(cls, name, classmethod(guarded))
    return cls
