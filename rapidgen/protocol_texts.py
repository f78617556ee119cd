"""The runtimes' reason and ack texts (runtime/spec/texts.yaml) generated into each runtime:
runtime/rapid_runtime/texts.py and runtime/cpp/include/rapid_runtime/texts.hpp.

    python -m rapidgen.protocol_texts            # rewrite what is stale
    python -m rapidgen.protocol_texts --check    # exit 1 when either file is stale

A text without placeholders becomes a constant named for its key in capitals, one with
placeholders a function named for its key taking them in `args` order. Every piece of a
text reaches the generated code as an escaped string literal (repr in Python, octal escapes
in C++), never as code. Errors in the table are located (file:line:col) and end the run.
"""
from __future__ import annotations

import argparse
import builtins
import keyword
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

from rapidgen.yamlread import load_yaml
from rapidgen.diagnostics import DiagnosticSink

ROOT = Path(__file__).resolve().parents[1]
TABLE = ROOT / "runtime" / "spec" / "texts.yaml"
PYTHON_OUT = ROOT / "runtime" / "rapid_runtime" / "texts.py"
CPP_OUT = ROOT / "runtime" / "cpp" / "include" / "rapid_runtime" / "texts.hpp"
RUST_OUT = ROOT / "runtime" / "rust" / "rapid_runtime" / "src" / "texts.rs"
SHOWN = "runtime/spec/texts.yaml"
HEADER = f"generated from {SHOWN}; do not edit (python -m rapidgen.protocol_texts)"

# placeholder type -> (Python annotation, Python expression of it, C++ parameter, C++ expression)
TYPES = {
    "text": ("str", "{}", "const std::string& {}", "{}"),
    "count": ("int", "str({})", "long long {}", "std::to_string({})"),
    "seconds": ("float", "format({}, '.1f')", "double {}", "detail::one_decimal({})"),
}
RUNTIMES = ("python", "cpp")  # `only:` values (the Rust runtime writes what C++ alone writes too)
# placeholder type -> (Rust parameter type, its format! spec)
RUST_TYPES = {"text": ("&str", ""), "count": ("usize", ""), "seconds": ("f64", ":.1")}
_KEY = re.compile(r"[a-z][a-z0-9_]*\Z")
_PIECE = re.compile(r"\{([^{}]*)\}")
# names a placeholder may not take: it becomes a parameter in both languages
_CPP_WORDS = frozenset("""alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t
char16_t char32_t class compl concept const consteval constexpr constinit const_cast continue co_await
co_return co_yield decltype default delete do double dynamic_cast else enum explicit export extern false
float for friend goto if inline int long mutable namespace new noexcept not not_eq nullptr operator or
or_eq private protected public register reinterpret_cast requires return short signed sizeof static
static_assert static_cast struct switch template this thread_local throw true try typedef typeid typename
union unsigned using virtual void volatile wchar_t while xor xor_eq std detail""".split())


class TextsError(Exception):
    """texts.yaml is not a valid table (the message is located)."""


@dataclass(frozen=True)
class Text:
    key: str
    pieces: tuple[str | tuple[str, str], ...]  # literal text, or (placeholder, type)
    args: tuple[tuple[str, str], ...]  # (name, type) in the order the function takes them
    when: str
    only: str | None

    @property
    def constant(self) -> bool:
        return not self.args

    @property
    def name(self) -> str:
        """The generated name: KEY for a constant, key for a function."""
        return self.key.upper() if self.constant else self.key

    @property
    def template(self) -> str:
        return "".join(p if isinstance(p, str) else "{" + p[0] + "}" for p in self.pieces)


def _bad_name(name: str) -> bool:
    return (not _KEY.match(name) or keyword.iskeyword(name) or name in _CPP_WORDS or hasattr(builtins, name))


def _pieces(text: str, args: dict, where: str) -> tuple[str | tuple[str, str], ...]:
    out: list[str | tuple[str, str]] = []
    pos = 0
    for m in _PIECE.finditer(text):
        if m.start() > pos:
            out.append(text[pos:m.start()])
        name = m.group(1)
        if name not in args:
            raise TextsError(f"{where}: placeholder {{{name}}} is not declared in args")
        out.append((name, args[name]))
        pos = m.end()
    if pos < len(text):
        out.append(text[pos:])
    if any(isinstance(p, str) and ("{" in p or "}" in p) for p in out):
        raise TextsError(f"{where}: a brace that is no {{placeholder}} in {text!r}")
    return tuple(out)


def load_table(path: Path = TABLE, shown: str = SHOWN) -> list[Text]:
    """The table's texts in file order; TextsError (located) when it is not a valid table."""
    sink = DiagnosticSink()
    doc = load_yaml(str(path), shown, sink)
    if doc is None or sink.has_errors:
        raise TextsError("\n".join(f"{d.loc}: {d.message}" for d in sink.errors) or f"{shown}: cannot be read")
    data = doc.data
    if not isinstance(data, dict) or set(data) != {"texts"} or not isinstance(data["texts"], dict):
        raise TextsError(f"{doc.loc(())}: the table is one mapping `texts:` of key -> entry")
    out: list[Text] = []
    names: set[str] = set()
    for key, entry in data["texts"].items():
        at = ("texts", key)
        if not isinstance(key, str) or _bad_name(key):
            raise TextsError(f"{doc.key_loc(at)}: key {key!r}: snake_case, not a keyword or builtin name")
        if not isinstance(entry, dict):
            raise TextsError(f"{doc.loc(at)}: {key}: an entry is a mapping (text, args, when, only)")
        unknown = set(entry) - {"text", "args", "when", "only"}
        if unknown:
            raise TextsError(f"{doc.key_loc((*at, sorted(unknown)[0]))}: {key}: unknown field {sorted(unknown)[0]!r}")
        text, when, args = entry.get("text"), entry.get("when"), entry.get("args") or {}
        if not isinstance(text, str) or not text:
            raise TextsError(f"{doc.loc((*at, 'text'))}: {key}: `text` is a non-empty string")
        if not isinstance(when, str) or not when.strip() or "\n" in when:
            raise TextsError(f"{doc.loc((*at, 'when'))}: {key}: `when` is one line saying when it is written")
        if "\\" in when or not when.isprintable():  # it becomes a comment: a C++ one ending in \ runs on
            raise TextsError(f"{doc.loc((*at, 'when'))}: {key}: `when` is plain text, no backslash")
        if not isinstance(args, dict):
            raise TextsError(f"{doc.loc((*at, 'args'))}: {key}: `args` maps each placeholder to its type")
        for name, kind in args.items():
            if not isinstance(name, str) or _bad_name(name):
                raise TextsError(f"{doc.key_loc((*at, 'args', name))}: {key}: placeholder name {name!r}: snake_case, "
                                 f"not a keyword or builtin name")
            if kind not in TYPES:
                raise TextsError(f"{doc.loc((*at, 'args', name))}: {key}: placeholder {name}: type {kind!r} is not "
                                 f"one of {', '.join(TYPES)}")
        only = entry.get("only")
        if only is not None and only not in RUNTIMES:
            raise TextsError(f"{doc.loc((*at, 'only'))}: {key}: `only` is one of {', '.join(RUNTIMES)}")
        pieces = _pieces(text, args, str(doc.loc((*at, "text"))))
        used = [p[0] for p in pieces if not isinstance(p, str)]
        for name in args:
            if name not in used:
                raise TextsError(f"{doc.key_loc((*at, 'args', name))}: {key}: placeholder {name} is not in the text")
        if len(used) != len(set(used)):
            raise TextsError(f"{doc.loc((*at, 'text'))}: {key}: a placeholder used twice")
        item = Text(key, pieces, tuple(args.items()), when.strip(), only)
        if item.name in names:
            raise TextsError(f"{doc.key_loc(at)}: {key}: a second text named {item.name}")
        names.add(item.name)
        out.append(item)
    return out


# ---- Python -------------------------------------------------------------------------------------

def _py_expr(t: Text) -> str:
    parts = [repr(p) if isinstance(p, str) else TYPES[p[1]][1].format(p[0]) for p in t.pieces]
    return " + ".join(parts)


def python_source(texts: Sequence[Text]) -> str:
    head = "\n".join([f"# {HEADER}",
                      '"""The reason and ack texts the runtime writes (runtime/spec/texts.yaml): one constant',
                      'or function per text, the same words as the C++ runtime\'s rapid_runtime/texts.hpp."""',
                      "from __future__ import annotations", "", "from typing import Final"])
    out = head + "\n"
    before = None  # the previous block's kind: a function is set off by two blank lines
    for t in texts:
        note = f"{t.when} (only the {t.only} runtime)" if t.only else t.when
        if t.constant:
            block = f"# {note}\n{t.name}: Final = {t.template!r}\n"
        else:
            params = ", ".join(f"{n}: {TYPES[k][0]}" for n, k in t.args)
            block = f"def {t.name}({params}) -> str:\n    # {note}\n    return {_py_expr(t)}\n"
        out += ("\n" if before == "constant" and t.constant else "\n\n") + block
        before = "constant" if t.constant else "function"
    return out


# ---- C++ ----------------------------------------------------------------------------------------

def cpp_literal(text: str) -> str:
    """text as a C++ string literal: printable ASCII as is (backslash and quote escaped),
    every other byte of its UTF-8 as a three-digit octal escape (which cannot run on)."""
    out = []
    for b in text.encode("utf-8"):
        c = chr(b)
        if c in '\\"':
            out.append("\\" + c)
        elif 0x20 <= b < 0x7f and c != "?":  # (no ?? trigraph, whatever the compiler's mode)
            out.append(c)
        else:
            out.append(f"\\{b:03o}")
    return '"' + "".join(out) + '"'


def _cpp_expr(t: Text) -> str:
    parts = [cpp_literal(p) if isinstance(p, str) else TYPES[p[1]][3].format(p[0]) for p in t.pieces]
    if isinstance(t.pieces[0], str):
        parts[0] = f"std::string({parts[0]})"  # (a std::string first: + then appends)
    return " + ".join(parts)


def cpp_source(texts: Sequence[Text]) -> str:
    out = [f"// {HEADER}",
           "// The reason and ack texts the runtime writes (runtime/spec/texts.yaml): one constant or",
           "// function per text, the same words as the Python runtime's rapid_runtime/texts.py.",
           "#ifndef RAPID_RUNTIME_TEXTS_HPP", "#define RAPID_RUNTIME_TEXTS_HPP", "",
           "#include <cstdio>", "#include <string>", "", "namespace rapid_runtime::texts {", ""]
    if any(k == "seconds" for t in texts for _, k in t.args):
        out += ["namespace detail {", "// Python's format(x, '.1f')", "inline std::string one_decimal(double x) {",
                "    char buf[64];", '    std::snprintf(buf, sizeof buf, "%.1f", x);', "    return buf;", "}",
                "}  // namespace detail", ""]
    for t in texts:
        note = f"{t.when} (only the {t.only} runtime)" if t.only else t.when
        out.append(f"// {note}")
        if t.constant:
            out.append(f"inline constexpr const char* {t.name} = {cpp_literal(t.template)};")
        else:
            params = ", ".join(TYPES[k][2].format(n) for n, k in t.args)
            out.append(f"inline std::string {t.name}({params}) {{ return {_cpp_expr(t)}; }}")
    out += ["", "}  // namespace rapid_runtime::texts", "", "#endif"]
    return "\n".join(out) + "\n"


# ---- Rust ---------------------------------------------------------------------------------------

def rust_literal(text: str, braces: bool) -> str:
    """text inside a Rust string literal: backslash and quote escaped, anything not printable
    as \\u{...}; braces doubled inside a format! string."""
    out = []
    for c in text:
        if c in '\\"':
            out.append("\\" + c)
        elif braces and c in "{}":
            out.append(c * 2)
        elif c.isprintable():
            out.append(c)
        else:
            out.append(f"\\u{{{ord(c):x}}}")
    return "".join(out)


def rust_source(texts: Sequence[Text]) -> str:
    out = [f"// {HEADER}",
           "//! Every reason and ack text the runtime writes: runtime/spec/texts.yaml's words, one constant",
           "//! or function per text (the Python runtime's texts.py and the C++ runtime's texts.hpp come from",
           "//! the same table). A text with placeholders is a function taking them in the table's `args`",
           "//! order: `text` a &str (a name from the wire shortened by the caller), `count` a usize,",
           "//! `seconds` an f64 written with one decimal.", ""]
    for t in texts:
        if t.only == "python":
            continue
        note = f"{t.when} (only the {t.only} runtime)" if t.only else t.when
        out.append(f"/// {note}")
        if t.constant:
            out.append(f'pub const {t.name}: &str = "{rust_literal(t.template, False)}";')
        else:
            params = ", ".join(f"{n}: {RUST_TYPES[k][0]}" for n, k in t.args)
            kinds = dict(t.args)
            body = "".join(rust_literal(p, True) if isinstance(p, str) else "{" + p[0] + RUST_TYPES[kinds[p[0]]][1] + "}"
                           for p in t.pieces)
            out += [f"pub fn {t.name}({params}) -> String {{", f'    format!("{body}")', "}"]
        out.append("")
    return "\n".join(out)


def outputs(texts: Sequence[Text] | None = None) -> dict[Path, str]:
    texts = load_table() if texts is None else texts
    return {PYTHON_OUT: python_source(texts), CPP_OUT: cpp_source(texts), RUST_OUT: rust_source(texts)}


def stale() -> list[Path]:
    """The generated files that differ from what the table gives (missing ones included)."""
    return [p for p, text in outputs().items()
            if not p.is_file() or p.read_text(encoding="utf-8") != text]


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m rapidgen.protocol_texts", description=__doc__.split("\n")[0])
    parser.add_argument("--check", action="store_true", help="exit 1 when a generated file is stale; write nothing")
    args = parser.parse_args(argv)
    try:
        wanted = outputs()
    except TextsError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    bad = 0
    for path, text in wanted.items():
        have = path.read_text(encoding="utf-8") if path.is_file() else None
        if have == text:
            continue
        shown = path.relative_to(ROOT)
        if args.check:
            print(f"stale: {shown} (python -m rapidgen.protocol_texts)", file=sys.stderr)
            bad = 1
        else:
            path.write_text(text, encoding="utf-8")
            print(f"wrote {shown}")
    return bad


if __name__ == "__main__":
    sys.exit(main())
