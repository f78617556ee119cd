"""The model pickled for another process, each IR object as the call of its constructor.

`dataclasses` pickles a frozen class with slots through its own __getstate__ and
__setstate__, Python functions that walk `fields()` for every object: half the time of
handing a 100-struct model to a worker went there. Here each IR class pickles as
`Class(*its init fields)` (an attrgetter, a C call, reads them), which unpickles through
the class's own __init__: the same object, in half the time. Everything else (the asset,
SourceLoc tuples, strings) pickles as usual.
"""
from __future__ import annotations

import copyreg
import dataclasses
import functools
import io
import pickle
from operator import attrgetter
from typing import IO, Any, Callable

from rapidgen.model import ir


def _reducer(cls: type) -> Callable[[Any], tuple]:
    names = [f.name for f in dataclasses.fields(cls) if f.init]
    get = attrgetter(*names)
    if len(names) == 1:
        return lambda obj: (cls, (get(obj),))
    return lambda obj: (cls, get(obj))


@functools.lru_cache(maxsize=None)
def _table() -> dict[type, Callable[[Any], Any]]:
    table: dict[type, Callable[[Any], Any]] = dict(copyreg.dispatch_table)
    for value in vars(ir).values():
        if (isinstance(value, type) and value.__module__ == ir.__name__ and dataclasses.is_dataclass(value)
                and any(f.init for f in dataclasses.fields(value))):
            table[value] = _reducer(value)
    return table


def dump(obj: object, file: IO[bytes]) -> None:
    """pickle.dump(obj, file), IR objects as constructor calls; pickle.load reads it."""
    pickler = pickle.Pickler(file, protocol=pickle.HIGHEST_PROTOCOL)
    pickler.dispatch_table = _table()
    pickler.dump(obj)


def dumps(obj: object) -> bytes:
    out = io.BytesIO()
    dump(obj, out)
    return out.getvalue()
