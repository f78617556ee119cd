"""The code `dataclasses` compiles for each class, kept per user from one run to the next.

Every @dataclass compiles the source of its methods (__init__, __repr__, __eq__, __hash__,
and for a frozen class __setattr__ and __delattr__) when its module is imported: ~90
classes and ~85 ms of a 100-struct `rapidgen generate`, more than parsing it. The texts
are the same on every run, so a rapidgen process (rapidgen.entry) keeps what it compiled
in the user's cache folder and execs that code instead of compiling the text again. The
functions made are the same: the code is the text compiled by this same Python, as
`exec(text)` would compile it (`"<string>"`, no inherited __future__ flags), and the
texts themselves are the keys, so a changed class or a changed `dataclasses` only misses.

One file per module, read when the module makes its first class and holding the code of
that module's classes as this process made them: a class edited or gone leaves nothing
behind, and a run reads only the modules it imports. The hook is a module global `exec`
in `dataclasses` (its `_create_fn` calls `exec` by name), set only where `_create_fn`
does so; library users of rapidgen never get it. A file is a marshal of
(format, Python version, module, {text: code}), read only when this user owns it and
nobody else may write it or its folder (it holds code that runs), and not written at all
under PYTHONDONTWRITEBYTECODE, as Python's own bytecode cache.
"""
from __future__ import annotations

import builtins
import marshal
import os
import re
import sys
from types import CodeType

_FORMAT = "rapidgen dataclass code 2"
_CODE = type(compile("", "<string>", "exec"))
_MODULE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)*")


def _folder() -> str | None:
    base = os.environ.get("XDG_CACHE_HOME", "")
    if not os.path.isabs(base):
        home = os.path.expanduser("~")
        if not os.path.isabs(home):
            return None
        base = os.path.join(home, ".cache")
    return os.path.join(base, "rapidgen")


def _trusted(st: os.stat_result) -> bool:
    """Owned by this user and writable by nobody else."""
    return not hasattr(os, "getuid") or (st.st_uid == os.getuid() and not st.st_mode & 0o022)


class CodeCache:
    """{source text: code object} for one Python, one file per module in `folder`."""

    def __init__(self, folder: str | None) -> None:
        self.folder = folder
        self.code: dict[str, CodeType] = {}  # every text of this process: read or compiled
        self.used: dict[str, dict[str, CodeType]] = {}  # module -> the texts its classes made here
        self.read: dict[str, frozenset[str]] = {}  # module -> the texts its file held
        self.compiled = 0  # texts compiled by this process (not found in the cache)
        self._folder_ok: bool | None = None

    def path(self, module: str) -> str | None:
        if self.folder is None or not _MODULE.fullmatch(module):
            return None
        return os.path.join(self.folder, module + ".marshal")

    def _load(self, module: str) -> dict[str, CodeType]:
        path = self.path(module)
        if path is None:
            return {}
        try:
            if self._folder_ok is None:
                self._folder_ok = _trusted(os.stat(self.folder))  # type: ignore[arg-type]
            if not self._folder_ok:
                return {}
            with open(path, "rb") as f:
                if not _trusted(os.fstat(f.fileno())):
                    return {}
                data = marshal.loads(f.read())
        except Exception:  # noqa: BLE001 (missing, unreadable or damaged: compile as usual)
            return {}
        if not (isinstance(data, tuple) and len(data) == 4 and data[0] == _FORMAT and data[1] == sys.version
                and data[2] == module and isinstance(data[3], dict)):
            return {}
        return {k: v for k, v in data[3].items() if type(k) is str and type(v) is _CODE}

    def exec(self, source, globals=None, locals=None):  # noqa: A002 (exec's own parameter names)
        """builtins.exec, with a text's compiled code taken from the cache."""
        if globals is None:  # exec's defaults: the caller's namespaces
            frame = sys._getframe(1)
            globals = frame.f_globals
            if locals is None:
                locals = frame.f_locals
        if type(source) is str:
            module = globals.get("__name__") if type(globals) is dict else None
            if type(module) is str and module not in self.read:
                found = self._load(module)
                self.read[module] = frozenset(found)
                self.code.update(found)
            code = self.code.get(source)
            if code is None:
                code = self.code[source] = compile(source, "<string>", "exec", dont_inherit=True)
                self.compiled += 1
            if type(module) is str:
                self.used.setdefault(module, {})[source] = code
            source = code
        elif isinstance(source, (bytes, bytearray)):  # compiled as exec would: no flags of this module
            source = compile(source, "<string>", "exec", dont_inherit=True)
        return builtins.exec(source, globals, locals)

    def save(self) -> None:
        """Write the file of each module whose classes this process made from other texts
        than its file held (new, changed or gone). Errors are ignored: a cache."""
        if self.folder is None or sys.dont_write_bytecode:
            return
        for module, entries in self.used.items():
            path = self.path(module)
            if path is None or self.read.get(module) == frozenset(entries):
                continue
            self.read[module] = frozenset(entries)
            tmp = f"{path}.{os.getpid()}.tmp"
            try:
                os.makedirs(self.folder, mode=0o700, exist_ok=True)
                fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
                try:
                    with os.fdopen(fd, "wb") as f:
                        f.write(marshal.dumps((_FORMAT, sys.version, module, entries)))
                    os.replace(tmp, path)
                except BaseException:
                    os.unlink(tmp)
                    raise
            except Exception:  # noqa: BLE001 (an unwritable or odd cache folder: run without)
                return


_installed: CodeCache | None = None


def install() -> CodeCache | None:
    """Serve `dataclasses` from the user's cache for the rest of this process (a rapidgen
    command's own process only); None where this Python's dataclasses does not exec by name."""
    global _installed
    import dataclasses

    if _installed is not None:
        return _installed
    code = getattr(getattr(dataclasses, "_create_fn", None), "__code__", None)
    if not isinstance(code, _CODE) or "exec" not in code.co_names or "exec" in vars(dataclasses):
        return None
    folder = _folder()
    tag = sys.implementation.cache_tag or "python"
    _installed = CodeCache(os.path.join(folder, f"dataclass-code.{tag}") if folder else None)
    dataclasses.exec = _installed.exec  # type: ignore[attr-defined]
    return _installed


def save() -> None:
    """Save the installed cache, if any (before the process ends)."""
    if _installed is not None:
        _installed.save()
