"""rapidgen.codecache: the code `dataclasses` compiles, kept per user between runs.

A CodeCache serving as dataclasses' `exec` makes the same classes as plain dataclasses;
a cache loaded from its saved files compiles nothing for the same class; save() writes
each module's file with the classes this process made of it (nothing stale stays), and
keeps off under dont_write_bytecode; files of another format/Python/owner or writable by
others are not read; the `rapidgen` program itself writes the cache and its output is
the same with it as without.

The pytest process never keeps the hook: it is set with monkeypatch for the making of a
class only, and install() runs in child processes only.
"""
from __future__ import annotations

import contextlib
import dataclasses
import inspect
import marshal
import os
import stat
import subprocess
import sys
import textwrap
import types
from pathlib import Path

import pytest

from rapidgen import codecache
from rapidgen.codecache import CodeCache

REPO = Path(__file__).resolve().parents[2]
CODE_TYPE = type(compile("", "<string>", "exec"))


# -- helpers ------------------------------------------------------------------------------------

def make_record():
    """A frozen slotted dataclass with defaults, a default_factory and a compare=False field."""
    @dataclasses.dataclass(frozen=True, slots=True)
    class Record:
        x: int
        y: int = 2
        tags: tuple = dataclasses.field(default_factory=lambda: ("t",))
        note: str = dataclasses.field(default="n", compare=False)
    return Record


def make_other():
    """A second class whose method texts differ from Record's."""
    @dataclasses.dataclass(order=True)
    class Other:
        alpha: str
        beta: float = 0.5
    return Other


def make_third():
    @dataclasses.dataclass(eq=True, frozen=True)
    class Third:
        gamma: bytes = b""
        delta: list = dataclasses.field(default_factory=list, hash=False)
    return Third


@contextlib.contextmanager
def hooked(monkeypatch, cache: CodeCache):
    """dataclasses' `exec` is the cache's for the body only (removed again after)."""
    with monkeypatch.context() as m:
        m.setattr(dataclasses, "exec", cache.exec, raising=False)
        yield
    assert "exec" not in vars(dataclasses)


def made_with(monkeypatch, cache: CodeCache, factory):
    with hooked(monkeypatch, cache):
        return factory()


def served_by(cache: CodeCache, func) -> bool:
    """True when func's code is a function made from one of the cache's code objects (the
    very object, not an equal one): the class was made through the cache."""
    func = inspect.unwrap(func)  # (__repr__ is wrapped against recursion)

    def nested(code):
        yield code
        for c in code.co_consts:
            if type(c) is CODE_TYPE:
                yield from nested(c)
    return any(func.__code__ is c for code in cache.code.values() for c in nested(code))


def record_behaviour(cls) -> dict:
    """What a Record class does, checked against what it must do; the observations are
    returned to compare a cached class with a plain one."""
    p = cls(1)
    assert (p.x, p.y, p.tags, p.note) == (1, 2, ("t",), "n")
    q = cls(1, 3, ("u",), "m")
    assert (q.x, q.y, q.tags, q.note) == (1, 3, ("u",), "m")
    assert cls(5).tags is not None and cls(5).tags == ("t",)
    with pytest.raises(TypeError):
        cls()  # x has no default
    assert repr(p).endswith("Record(x=1, y=2, tags=('t',), note='n')")
    # eq and hash ignore the compare=False field, not the others
    assert cls(1, note="a") == cls(1, note="b")
    assert hash(cls(1, note="a")) == hash(cls(1, note="b"))
    assert cls(1) != cls(2)
    assert cls(1) != cls(1, tags=("v",))
    assert (cls(1) == (1, 2, ("t",))) is False
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.x = 5
    with pytest.raises(dataclasses.FrozenInstanceError):
        del p.y
    try:  # not a field: Python 3.11's frozen+slots __setattr__ fails with TypeError (its bug); as plain
        p.other = 1
    except Exception as exc:  # noqa: BLE001
        other_set = type(exc).__name__
    else:
        other_set = "set"
    r = dataclasses.replace(p, y=7)
    assert (r.x, r.y, r.tags, r.note) == (1, 7, ("t",), "n") and p.y == 2
    fields = dataclasses.fields(cls)
    assert [f.name for f in fields] == ["x", "y", "tags", "note"]
    assert [f.compare for f in fields] == [True, True, True, False]
    assert cls.__slots__ == ("x", "y", "tags", "note") and not hasattr(p, "__dict__")
    assert cls.__match_args__ == ("x", "y", "tags", "note")
    return {
        "repr": repr(q), "hash": hash(p), "hash_q": hash(q), "eq": p == q,
        "init": str(inspect.signature(cls.__init__)),
        "fields": [(f.name, f.default, f.compare, f.hash, f.init, f.repr) for f in fields],
        "astuple": dataclasses.astuple(q), "asdict": dataclasses.asdict(q),
        "replace": repr(dataclasses.replace(q, note="z")),
        "params": repr(cls.__dataclass_params__), "other_set": other_set,
    }


@pytest.fixture(autouse=True)
def _never_installed():
    """No test leaves (or finds) the hook in this process's dataclasses."""
    assert "exec" not in vars(dataclasses) and codecache._installed is None
    yield
    assert "exec" not in vars(dataclasses) and codecache._installed is None


@pytest.fixture
def writable(monkeypatch):
    """save() writes (the test runs may have PYTHONDONTWRITEBYTECODE=1)."""
    monkeypatch.setattr(sys, "dont_write_bytecode", False)


MODULE = make_record.__module__  # the module the test classes are made in: their file's name


@pytest.fixture
def cache_dir(tmp_path) -> str:
    folder = tmp_path / "cache" / "rapidgen" / "dataclass-code.test"
    folder.mkdir(parents=True)
    folder.chmod(0o700)
    return str(folder)


def module_file(folder: str) -> str:
    path = CodeCache(folder).path(MODULE)
    assert path is not None
    return path


def write_raw(path: str, data, mode: int = 0o600) -> None:
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else marshal.dumps(data))
    os.chmod(path, mode)


def some_entries() -> dict:
    """Real {text: code} entries, as a file would hold (those of Record)."""
    c = CodeCache(None)
    with pytest.MonkeyPatch.context() as m:
        m.setattr(dataclasses, "exec", c.exec, raising=False)
        make_record()
    assert c.compiled > 0 and c.code
    return dict(c.code)


def saved(path: str) -> dict:
    fmt, version, module, code = marshal.loads(Path(path).read_bytes())
    assert (fmt, version, module) == (codecache._FORMAT, sys.version, MODULE)
    return code


# -- 1. the classes made through the cache -------------------------------------------------------

def test_cached_class_behaves_as_plain_and_second_making_compiles_nothing(monkeypatch, writable, cache_dir):
    plain = make_record()
    assert not served_by(CodeCache(None), plain.__init__)
    expected = record_behaviour(plain)

    first = CodeCache(cache_dir)
    cls = made_with(monkeypatch, first, make_record)
    assert first.read == {MODULE: frozenset()}  # no file yet
    # __init__, __repr__, __eq__, __hash__, __setattr__, __delattr__: each text compiled here
    assert first.compiled >= 6 and len(first.code) == first.compiled
    assert any("def __init__" in t for t in first.code) and any("FrozenInstanceError" in t for t in first.code)
    for name in ("__init__", "__repr__", "__eq__", "__hash__", "__setattr__", "__delattr__"):
        assert served_by(first, getattr(cls, name)), name
    assert cls is not plain
    assert record_behaviour(cls) == expected

    first.save()
    path = module_file(cache_dir)
    assert saved(path) == first.code
    assert stat.S_IMODE(os.stat(path).st_mode) == 0o600

    second = CodeCache(cache_dir)
    again = made_with(monkeypatch, second, make_record)
    assert second.compiled == 0 and set(second.code) == set(first.code)
    for name in ("__init__", "__repr__", "__eq__", "__hash__", "__setattr__", "__delattr__"):
        assert served_by(second, getattr(again, name)), name
    assert record_behaviour(again) == expected
    # the same classes from the same texts: nothing to save, the file is left as it was
    before = os.stat(path)
    second.save()
    after = os.stat(path)
    assert (after.st_ino, after.st_mtime_ns) == (before.st_ino, before.st_mtime_ns)


def test_loaded_code_equals_what_exec_would_compile(cache_dir, writable, monkeypatch):
    c = CodeCache(cache_dir)
    made_with(monkeypatch, c, make_record)
    c.save()
    loaded = CodeCache(cache_dir)._load(MODULE)
    assert loaded
    for text, code in loaded.items():
        assert code == compile(text, "<string>", "exec", dont_inherit=True)
        assert code.co_filename == "<string>"


def test_exec_of_a_text_and_of_the_caller_namespaces():
    c = CodeCache(None)
    ns: dict = {}
    c.exec("y = 2\ndef f(a: int): return a + y", ns)
    assert ns["y"] == 2 and ns["f"](1) == 3 and ns["f"].__annotations__ == {"a": int}  # no inherited __future__
    assert c.compiled == 1
    c.exec("y = 2\ndef f(a: int): return a + y", {})
    assert c.compiled == 1  # the same text: from the cache
    g: dict = {}
    loc: dict = {}
    c.exec("z = 5", g, loc)
    assert loc == {"z": 5} and "z" not in g
    probe: list = []
    c.exec("probe.append(__name__)")  # no namespaces: the caller's, as builtins.exec
    assert probe == [__name__]
    code = compile("w = 1", "<x>", "exec")
    c.exec(code, ns)
    assert ns["w"] == 1 and c.compiled == 3 and code not in c.code.values()


# -- 2. save() ----------------------------------------------------------------------------------

def test_save_writes_nothing_when_no_class_was_made(cache_dir, writable):
    CodeCache(cache_dir).save()
    assert os.listdir(cache_dir) == []


def test_save_writes_when_compiled_and_creates_the_folder(tmp_path, writable, monkeypatch):
    folder = tmp_path / "new" / "rapidgen" / "dataclass-code.test"
    c = CodeCache(str(folder))
    made_with(monkeypatch, c, make_other)
    assert c.compiled > 0
    c.save()
    path = Path(c.path(MODULE))
    assert saved(str(path)) == c.code
    assert stat.S_IMODE(path.stat().st_mode) == 0o600
    assert stat.S_IMODE(folder.stat().st_mode) & 0o077 == 0
    assert os.listdir(folder) == [path.name]  # no temporary file left


def test_a_module_file_holds_the_classes_this_process_made_of_it(cache_dir, writable, monkeypatch):
    """A run that makes more classes of the module adds them; one that makes fewer (a class
    edited or gone) leaves only its own: nothing stale stays in the file."""
    a = CodeCache(cache_dir)
    made_with(monkeypatch, a, make_record)
    a.save()
    record_texts = set(a.code)
    b = CodeCache(cache_dir)
    cls_b = made_with(monkeypatch, b, make_other)
    made_with(monkeypatch, b, make_record)
    assert b.compiled == len(set(b.code) - record_texts) > 0  # Record's texts came from the file
    b.save()
    assert set(saved(module_file(cache_dir))) == set(b.code) > record_texts
    c = CodeCache(cache_dir)
    again = made_with(monkeypatch, c, make_other)
    assert c.compiled == 0
    c.save()
    other_texts = set(saved(module_file(cache_dir)))
    assert other_texts == set(b.code) - record_texts  # Record's gone with the run that made none
    assert again("x", 1.0) < again("y") and again("q") == again("q", 0.5) and again("q") != again("q", 1.5)
    assert repr(again("q")) == repr(cls_b("q"))


def test_modules_have_files_of_their_own(cache_dir, writable, monkeypatch):
    c = CodeCache(cache_dir)
    other = types.ModuleType("some.other_module")
    monkeypatch.setitem(sys.modules, other.__name__, other)
    ns = vars(other)
    with hooked(monkeypatch, c):
        exec("import dataclasses\n@dataclasses.dataclass\nclass Q:\n    a: int = 0\n", ns)
        make_record()
    c.save()
    assert sorted(os.listdir(cache_dir)) == sorted([f"{MODULE}.marshal", "some.other_module.marshal"])
    assert ns["Q"]() == ns["Q"](0)
    for odd in ("../escape", "a/b", "", "x y", ".hidden"):
        assert c.path(odd) is None  # not a module name: not cached, never a path outside the folder


def test_save_not_under_dont_write_bytecode(cache_dir, monkeypatch):
    monkeypatch.setattr(sys, "dont_write_bytecode", True)
    c = CodeCache(cache_dir)
    made_with(monkeypatch, c, make_record)
    assert c.compiled > 0
    c.save()
    assert os.listdir(cache_dir) == []


def test_save_errors_are_ignored(tmp_path, writable, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    c = CodeCache(str(blocker / "rapidgen" / "dc"))
    made_with(monkeypatch, c, make_record)
    c.save()  # the folder cannot be made: no error, nothing written
    assert blocker.read_text() == "not a folder"
    none = CodeCache(None)
    made_with(monkeypatch, none, make_record)
    none.save()


# -- 3. files that are not read ----------------------------------------------------------------

def test_a_good_file_is_read(cache_dir):
    entries = some_entries()
    write_raw(module_file(cache_dir), (codecache._FORMAT, sys.version, MODULE, entries))
    assert CodeCache(cache_dir)._load(MODULE) == entries


@pytest.mark.parametrize("kind", ["damaged", "truncated", "empty", "format", "version", "module", "not-a-tuple",
                                  "long-tuple", "not-a-dict"])
def test_refused_contents_load_as_empty(cache_dir, monkeypatch, kind):
    entries = some_entries()
    good = marshal.dumps((codecache._FORMAT, sys.version, MODULE, entries))
    data = {
        "damaged": b"\x00\xffnot marshal at all" + good[40:],
        "truncated": good[: len(good) // 2],
        "empty": b"",
        "format": ("rapidgen dataclass code 1", sys.version, MODULE, entries),
        "version": (codecache._FORMAT, sys.version + " (another build)", MODULE, entries),
        "module": (codecache._FORMAT, sys.version, MODULE + "_other", entries),
        "not-a-tuple": [codecache._FORMAT, sys.version, MODULE, entries],
        "long-tuple": (codecache._FORMAT, sys.version, MODULE, entries, None),
        "not-a-dict": (codecache._FORMAT, sys.version, MODULE, list(entries.items())),
    }[kind]
    write_raw(module_file(cache_dir), data)
    c = CodeCache(cache_dir)
    assert c._load(MODULE) == {}
    cls = made_with(monkeypatch, c, make_record)
    assert c.compiled > 0
    assert record_behaviour(cls) == record_behaviour(make_record())


def test_group_or_other_writable_file_is_not_read(cache_dir, monkeypatch):
    path = module_file(cache_dir)
    write_raw(path, (codecache._FORMAT, sys.version, MODULE, some_entries()))
    for mode in (0o666, 0o620, 0o602):
        os.chmod(path, mode)
        assert CodeCache(cache_dir)._load(MODULE) == {}, oct(mode)
    c = CodeCache(cache_dir)
    cls = made_with(monkeypatch, c, make_record)
    assert c.compiled > 0 and record_behaviour(cls) == record_behaviour(make_record())
    os.chmod(path, 0o644)  # readable by others is fine
    assert CodeCache(cache_dir)._load(MODULE)


def test_file_in_group_or_other_writable_folder_is_not_read(cache_dir, monkeypatch):
    write_raw(module_file(cache_dir), (codecache._FORMAT, sys.version, MODULE, some_entries()))
    try:
        for mode in (0o777, 0o770, 0o703):
            os.chmod(cache_dir, mode)
            assert CodeCache(cache_dir)._load(MODULE) == {}, oct(mode)
        c = CodeCache(cache_dir)
        cls = made_with(monkeypatch, c, make_record)
        assert c.compiled > 0 and record_behaviour(cls) == record_behaviour(make_record())
    finally:
        os.chmod(cache_dir, 0o700)
    assert CodeCache(cache_dir)._load(MODULE)


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() != 0, reason="chown to another user needs root")
def test_file_or_folder_of_another_user_is_not_read(cache_dir):
    path = module_file(cache_dir)
    write_raw(path, (codecache._FORMAT, sys.version, MODULE, some_entries()))
    assert CodeCache(cache_dir)._load(MODULE)
    os.chown(path, os.getuid() + 4321, -1)
    assert CodeCache(cache_dir)._load(MODULE) == {}
    os.chown(path, os.getuid(), -1)
    os.chown(cache_dir, os.getuid() + 4321, -1)
    try:
        assert CodeCache(cache_dir)._load(MODULE) == {}
    finally:
        os.chown(cache_dir, os.getuid(), -1)


def test_entries_of_other_types_are_dropped(cache_dir):
    entries = some_entries()
    text, code = next(iter(entries.items()))
    other_text = next(t for t in entries if t != text)
    data = {text: code, other_text: "not code", b"bytes key": code, 3: code, (text,): code, "x": 1.5}
    write_raw(module_file(cache_dir), (codecache._FORMAT, sys.version, MODULE, data))
    assert CodeCache(cache_dir)._load(MODULE) == {text: code}


# -- 4. the rapidgen program, end to end ---------------------------------------------------------

IDL = """\
module shapes {
  struct Point { long x; long y; };
  struct Label { string text; double size; };
  struct Shape { @key long id; Point origin; sequence<Point, 8> points; Label label; };
};
"""


def _env(cache: Path | None, **extra: str) -> dict:
    env = dict(os.environ)
    for name in ("PYTHONDONTWRITEBYTECODE", "RAPIDGEN_JOBS", "XDG_CACHE_HOME"):
        env.pop(name, None)
    if cache is not None:
        env["XDG_CACHE_HOME"] = str(cache)
    env.update(extra)
    return env


def _generate(idl: Path, out: Path, env: dict) -> None:
    proc = subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(idl), "--lang", "python,cpp,rust,qos",
                           "-o", str(out)], cwd=REPO, env=env, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stdout + proc.stderr


def _tree(root: Path) -> dict[str, bytes]:
    files = {p.relative_to(root).as_posix(): p.read_bytes() for p in root.rglob("*") if p.is_file()}
    assert files
    return files


def _cache_folder(cache: Path) -> Path:
    return cache / "rapidgen" / f"dataclass-code.{sys.implementation.cache_tag}"


def _files(folder: Path) -> dict[str, tuple]:
    return {p.name: (p.stat().st_ino, p.stat().st_mtime_ns, p.stat().st_size) for p in folder.iterdir()}


def test_rapidgen_program_writes_and_uses_the_cache(tmp_path):
    idl = tmp_path / "shapes.idl"
    idl.write_text(IDL)
    cache = tmp_path / "cache"
    env = _env(cache)
    _generate(idl, tmp_path / "out1", env)
    folder = _cache_folder(cache)
    ir = folder / "rapidgen.model.ir.marshal"
    assert ir.is_file()  # the front end's classes (the parent) ...
    assert (folder / "rapidgen.backends.qos.view.marshal").is_file()  # ... and a forked worker's
    assert stat.S_IMODE(ir.stat().st_mode) == 0o600
    assert stat.S_IMODE(folder.stat().st_mode) & 0o077 == 0
    fmt, version, module, code = marshal.loads(ir.read_bytes())
    assert (fmt, version, module) == (codecache._FORMAT, sys.version, "rapidgen.model.ir")
    assert code and all(type(k) is str and type(v) is CODE_TYPE for k, v in code.items())
    assert any("__init__" in k for k in code)
    assert not [n for n in os.listdir(folder) if not n.endswith(".marshal")]  # no temporary file left
    first = _tree(tmp_path / "out1")
    assert any(n.startswith("python/") for n in first) and any(n.startswith("cpp/") for n in first)
    files = _files(folder)

    _generate(idl, tmp_path / "out2", env)
    assert _tree(tmp_path / "out2") == first
    # everything the second run needed was in the files: it compiled nothing, so wrote nothing
    assert _files(folder) == files

    _generate(idl, tmp_path / "out3", _env(cache, RAPIDGEN_JOBS="1"))
    assert _tree(tmp_path / "out3") == first

    # the same output with no cache at all (PYTHONDONTWRITEBYTECODE: none written either)
    fresh = tmp_path / "fresh-cache"
    _generate(idl, tmp_path / "out4", _env(fresh, PYTHONDONTWRITEBYTECODE="1"))
    assert _tree(tmp_path / "out4") == first
    assert not (fresh / "rapidgen").exists()


# -- 5. install(), in child processes only -----------------------------------------------------

def _python(code: str, cache: Path) -> str:
    proc = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], cwd=REPO, env=_env(cache),
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return proc.stdout.strip()


def test_install_without_exec_in_create_fn_returns_none(tmp_path):
    out = _python("""
        import dataclasses
        def _create_fn(name, args, body, *, globals=None, locals=None, return_type=dataclasses.MISSING):
            raise AssertionError("not called")
        dataclasses._create_fn = _create_fn
        from rapidgen import codecache
        print(codecache.install(), "exec" in vars(dataclasses), codecache._installed)
    """, tmp_path / "cache")
    assert out == "None False None"


def test_install_when_dataclasses_has_exec_already_returns_none(tmp_path):
    out = _python("""
        import dataclasses
        mine = exec
        dataclasses.exec = mine
        from rapidgen import codecache
        print(codecache.install(), dataclasses.exec is mine, codecache._installed)
    """, tmp_path / "cache")
    assert out == "None True None"


def test_install_hooks_dataclasses_with_the_users_cache_file(tmp_path):
    cache = tmp_path / "cache"
    out = _python("""
        import dataclasses, sys
        from rapidgen import codecache
        c = codecache.install()
        assert codecache.install() is c and codecache._installed is c
        assert dataclasses.exec == c.exec
        @dataclasses.dataclass
        class K:
            a: int = 1
        assert K() == K(1) and repr(K(2)) == "K(a=2)"
        sys.dont_write_bytecode = False
        print(c.folder, c.compiled > 0)
        codecache.save()
    """, cache)
    folder = _cache_folder(cache)
    assert out == f"{folder} True"
    assert any("__init__" in t for t in marshal.loads((folder / "__main__.marshal").read_bytes())[3])


def test_cache_folder_from_xdg_or_home(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert codecache._folder() == str(tmp_path / "xdg" / "rapidgen")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    for relative in ("", "relative/xdg"):
        monkeypatch.setenv("XDG_CACHE_HOME", relative)
        assert codecache._folder() == str(tmp_path / "home" / ".cache" / "rapidgen")


# -- odd inputs: a _create_fn without code, a bytes source ----------------------------------

def test_install_with_create_fn_without_code_returns_none(tmp_path):
    proc = subprocess.run([sys.executable, "-c", textwrap.dedent("""
        import dataclasses, functools
        dataclasses._create_fn = functools.partial(print)  # callable, no __code__
        from rapidgen import codecache
        print(codecache.install(), "exec" in vars(dataclasses))
    """)], cwd=REPO, env=_env(tmp_path / "cache"), capture_output=True, text=True, timeout=60)
    if "TypeError" in proc.stderr:
        raise TypeError(proc.stderr.strip().splitlines()[-1])
    assert proc.returncode == 0 and proc.stdout.strip() == "None False", proc.stderr


def test_exec_of_bytes_source_is_as_builtins_exec():
    ns: dict = {}
    CodeCache(None).exec(b"def f(a: int): pass", ns)
    assert ns["f"].__annotations__ == {"a": int}
