"""The one Jinja2 environment factory: strict, whitespace-controlled, filters in one place.

Templates live in the top-level templates/<target>/; the package reaches them through the
link rapidgen/templates (a copy in the wheel, so a plain `pip install .` ships them), one per artifact, `<artifact>.<ext>.j2`, plus `_macros.j2`.
They only print what the view layer decided: loops, precomputed booleans, macros.

Precompiled templates. Compiling the templates (Jinja2's parser and code generator, then
Python's compiler) cost about a quarter of a second on every run. The package therefore
ships each template already compiled to Python, in rapidgen/backends/precompiled/ (plain
modules: Python keeps their bytecode in __pycache__ like any other module's, and a
read-only install simply goes without). Each module records a KEY: the Jinja2 version,
the environment's settings and a digest of the template's source. A template is taken from
its module only when the key matches the source read now; otherwise (a template edited
since, another Jinja2) it is compiled from source, as before. The module holds the very
code Jinja2 would generate (tests/unit/test_precompiled.py compares them), so the output
is the same either way; only the time differs. Nothing is written at run time.

    python -m rapidgen.backends.templating --write   # refresh the modules after editing a template
    python -m rapidgen.backends.templating --check   # list stale ones (exit 1 if any)
"""
from __future__ import annotations

import functools
import hashlib
import importlib.util
import re
import sys
from pathlib import Path
from typing import Callable, MutableMapping

import jinja2

from rapidgen.backends import escape
from rapidgen.speed_devices import without

# Every input string a template prints goes through one of these, or (XML targets) through
# escape.xml_text, which replaces plain autoescape; rapidgen/backends/escape.py says what
# each guarantees.
FILTERS = {
    "py_str": escape.py_str,  # a Python string literal (value round-trips)
    "docstring": escape.py_docstring,  # inside """...""" (value round-trips)
    "comment": escape.line_comment,  # after `#` in Python or TOML
    "toml_str": escape.toml_str,  # a TOML basic string (value round-trips)
    "xml_comment": escape.xml_comment,  # inside <!-- ... -->
    "cpp_str": escape.cpp_str,  # a C++ string literal (value: the UTF-8 bytes)
    "cpp_comment": escape.cpp_comment,  # after `//` in C++ (or `#` in CMake)
    "rust_str": escape.rust_str,  # a Rust string literal (value round-trips)
    "rust_comment": escape.rust_comment,  # after `//` or `///` in Rust
}


# Targets whose templates are all XML: every printed value goes through escape.xml_text
# (markup escaped, whitespace a parser would normalize as character references).
XML_TARGETS = frozenset({"qos"})

TEMPLATE_ROOT = Path(__file__).resolve().parent.parent / "templates"  # the link rapidgen/templates
PRECOMPILED_PACKAGE = "rapidgen.backends.precompiled"
PRECOMPILED_DIR = Path(__file__).resolve().parent / "precompiled"

# What the generated code depends on besides the source: bump SETTINGS_VERSION when an
# option below or the autoescape rule changes.
SETTINGS_VERSION = 1
_OPTIONS = {"trim_blocks": True, "lstrip_blocks": True, "keep_trailing_newline": True}


def _autoescape(name: str | None) -> bool:
    return name is not None and name.endswith(".xml.j2")


class _Loader(jinja2.BaseLoader):
    """The target's templates from the package, each taken from its precompiled module
    when that module was compiled from the same source by the same Jinja2."""

    def __init__(self, target: str) -> None:
        self.target = target
        self.source_loader = jinja2.PackageLoader("rapidgen", f"templates/{target}")

    def get_source(self, environment: jinja2.Environment, template: str) -> tuple[str, str | None, Callable[[], bool] | None]:
        return self.source_loader.get_source(environment, template)

    def list_templates(self) -> list[str]:
        return self.source_loader.list_templates()

    def load(self, environment: jinja2.Environment, name: str,
             globals: MutableMapping[str, object] | None = None) -> jinja2.Template:
        source, filename, uptodate = self.get_source(environment, name)
        code = precompiled_code(self.target, name, source)
        if code is None:
            code = environment.compile(source, name, filename)
        # What Template.from_code does, with the template's own file named in tracebacks.
        namespace = {"environment": environment, "__file__": filename or name}
        exec(code, namespace)
        template = environment.template_class.from_module_dict(environment, namespace, globals or {})
        template._uptodate = uptodate
        return template


@functools.lru_cache(maxsize=None)
def environment(target: str) -> jinja2.Environment:
    return _environment(target, _Loader(target))


def _environment(target: str, loader: jinja2.BaseLoader | None) -> jinja2.Environment:
    env = jinja2.Environment(
        loader=loader,
        undefined=jinja2.StrictUndefined,
        autoescape=_autoescape,
        finalize=escape.xml_text if target in XML_TARGETS else None,
        auto_reload=False,  # templates do not change during a run
        trim_blocks=_OPTIONS["trim_blocks"],
        lstrip_blocks=_OPTIONS["lstrip_blocks"],
        keep_trailing_newline=_OPTIONS["keep_trailing_newline"],
    )
    env.filters.update(FILTERS)
    return env


def render(target: str, template: str, **context: object) -> str:
    return environment(target).get_template(template).render(**context)


def names(target: str, root: Path = TEMPLATE_ROOT) -> list[str]:
    """The target's templates, as render() names them."""
    folder = root / target
    return [path.relative_to(folder).as_posix() for path in sorted(folder.rglob("*.j2"))]


# -- precompiled templates ----------------------------------------------------------------
def key(target: str, name: str, source: str) -> str:
    """What a precompiled module must have been made from to stand in for the source."""
    settings = f"{sorted(_OPTIONS.items())}|xml={target in XML_TARGETS}|v{SETTINGS_VERSION}"
    text = "\0".join((jinja2.__version__, settings, target, name, source))
    return hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest()


def module_name(target: str, name: str) -> str:
    """'python', 'module.py.j2' -> 'python__module_py_j2' (a Python identifier)."""
    return re.sub(r"[^A-Za-z0-9]", "_", target) + "__" + re.sub(r"[^A-Za-z0-9]", "_", name)


_KEY_LINE = re.compile(r'^KEY = "([0-9a-f]{64})"$', re.M)


def precompiled_code(target: str, name: str, source: str):
    """The code object of the template's precompiled module, or None when there is none or
    it was made from another source, settings or Jinja2."""
    if without("precompiled-templates"):
        return None
    module = f"{PRECOMPILED_PACKAGE}.{module_name(target, name)}"
    try:
        spec = importlib.util.find_spec(module)
    except (ImportError, ValueError):
        return None
    if spec is None or spec.loader is None or spec.origin is None:
        return None
    try:
        with open(spec.origin, encoding="utf-8") as f:
            head = f.read(512)
    except OSError:
        return None
    m = _KEY_LINE.search(head)
    if m is None or m.group(1) != key(target, name, source):
        return None
    get_code = getattr(spec.loader, "get_code", None)
    return get_code(module) if get_code is not None else None  # the bytecode in __pycache__ when fresh


def module_text(target: str, name: str, source: str) -> str:
    """The precompiled module of one template: its key, then what Jinja2 generates."""
    code = _environment(target, None).compile(source, name, None, raw=True)
    return ("# mypy: ignore-errors\n"
            f"# Template templates/{target}/{name}, compiled by Jinja2 {jinja2.__version__}; do not edit.\n"
            f"# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).\n"
            f'KEY = "{key(target, name, source)}"\n' + code + "\n")


def _templates(root: Path = TEMPLATE_ROOT) -> list[tuple[str, str, Path]]:
    return [(folder.name, name, folder / name)
            for folder in sorted(p for p in root.iterdir() if p.is_dir()) for name in names(folder.name, root)]


def stale(root: Path = TEMPLATE_ROOT, folder: Path = PRECOMPILED_DIR) -> tuple[list[str], list[str]]:
    """(templates whose module is missing or out of date, modules no template has)."""
    wanted, behind = set(), []
    for target, name, path in _templates(root):
        module = folder / f"{module_name(target, name)}.py"
        wanted.add(module.name)
        text = module.read_text(encoding="utf-8") if module.is_file() else ""
        m = _KEY_LINE.search(text[:512])
        if m is None or m.group(1) != key(target, name, path.read_text(encoding="utf-8")):
            behind.append(f"{target}/{name}")
    extra = sorted(p.name for p in folder.glob("*.py") if p.name != "__init__.py" and p.name not in wanted)
    return behind, extra


def write(root: Path = TEMPLATE_ROOT, folder: Path = PRECOMPILED_DIR) -> list[str]:
    """(Re)write every template's module; remove modules no template has. Returns what changed."""
    folder.mkdir(exist_ok=True)
    init = folder / "__init__.py"
    if not init.exists():
        init.write_text('"""Templates compiled by Jinja2 (rapidgen/backends/templating.py); do not edit."""\n')
    changed, names = [], set()
    for target, name, path in _templates(root):
        module = folder / f"{module_name(target, name)}.py"
        if module.name in names:
            raise SystemExit(f"two templates map to {module.name}")
        names.add(module.name)
        text = module_text(target, name, path.read_text(encoding="utf-8"))
        if not module.is_file() or module.read_text(encoding="utf-8") != text:
            module.write_text(text, encoding="utf-8")
            changed.append(module.name)
    for extra in folder.glob("*.py"):
        if extra.name != "__init__.py" and extra.name not in names:
            extra.unlink()
            changed.append(f"removed {extra.name}")
    return changed


def main(argv: list[str] | None = None) -> int:
    import argparse
    parser = argparse.ArgumentParser(prog="python -m rapidgen.backends.templating",
                                     description="precompiled templates: refresh or check them")
    what = parser.add_mutually_exclusive_group(required=True)
    what.add_argument("--write", action="store_true", help="compile every template into rapidgen/backends/precompiled/")
    what.add_argument("--check", action="store_true", help="list stale precompiled templates; exit 1 if any")
    args = parser.parse_args(argv)
    if args.write:
        for line in write():
            print(line)
        return 0
    behind, extra = stale()
    for name in behind:
        print(f"stale: {name}")
    for name in extra:
        print(f"no template: {name}")
    return 1 if behind or extra else 0


if __name__ == "__main__":
    sys.exit(main())
