"""The C-preprocessor subset that IDL files use.

Supported: `#include "x"` / `<x>` (including file's folder first for quotes, then -I
paths), include-once by real path (files reached by different paths are read once),
include cycles as errors, `#define`/`#undef` of object-like names, `#ifdef`, `#ifndef`,
`#if`/`#elif` with `defined`, integer arithmetic and logic, `#else`, `#endif`,
`#error`/`#warning`. `#pragma keylist` lines are kept verbatim for the grammar (so they
are resolved in their module scope); other pragmas are dropped with a warning.

Comments are tracked so that a directive-looking line inside a block comment, or a
`//@copy-c-declaration #if ...` directive comment, is never preprocessed. The output is
one text plus a map from each output line back to (file, line), so every later
diagnostic names the original file and line.
"""
from __future__ import annotations

import os
import re
from dataclasses import dataclass, field

from rapidgen.diagnostics import DiagnosticSink, SourceLoc
from rapidgen.idl.ifexpr import evaluate as evaluate_condition

MAX_INPUT_BYTES = 64 * 1024 * 1024
MAX_INCLUDE_DEPTH = 64

_DIRECTIVE = re.compile(r"^\s*#\s*([A-Za-z_]\w*)?(.*)$")
_IDENT = re.compile(r"[A-Za-z_]\w*")


@dataclass
class PreprocessResult:
    text: str
    line_map: list[tuple[str, int]]
    sources: dict[str, str] = field(default_factory=dict)  # display path -> text
    files: list[str] = field(default_factory=list)  # display paths, in reading order
    # (file, line) -> column of a trailing `//@key` comment (RTI's key marker)
    key_comments: dict[tuple[str, int], int] = field(default_factory=dict)

    def origin(self, out_line: int) -> tuple[str, int]:
        """(file, line) of a 1-based output line."""
        if 1 <= out_line <= len(self.line_map):
            return self.line_map[out_line - 1]
        if self.line_map:
            f, ln = self.line_map[-1]
            return f, ln + 1
        return ("<input>", 1)


def display_path(path: str) -> str:
    """Paths shown to the user: relative to the working folder when inside it."""
    norm = os.path.normpath(path)
    if os.path.isabs(norm):
        try:
            rel = os.path.relpath(norm)
        except ValueError:
            return norm
        if not rel.startswith(".."):
            return rel
    return norm


@dataclass
class _Cond:
    active: bool  # this branch's lines are emitted
    taken: bool  # some branch of this #if group was taken
    parent_active: bool
    loc: SourceLoc
    seen_else: bool = False


class Preprocessor:
    def __init__(self, include_dirs: list[str], sink: DiagnosticSink,
                 defines: dict[str, str] | None = None) -> None:
        self.include_dirs = list(include_dirs)
        self.sink = sink
        self.macros: dict[str, str] = dict(defines or {})
        self.out: list[str] = []
        self.line_map: list[tuple[str, int]] = []
        self.sources: dict[str, str] = {}
        self.files: list[str] = []
        self.key_comments: dict[tuple[str, int], int] = {}
        self._done: set[str] = set()
        self._stack: list[str] = []  # real paths being read, for cycle detection

    # -- files -------------------------------------------------------------------
    def run(self, paths: list[str]) -> PreprocessResult:
        for d in self.include_dirs:
            if not os.path.isdir(d):
                self.sink.warning("RG0112", f"include folder '{d}' does not exist",
                                  SourceLoc("<command line>", 0, 0), "check the -I option")
        for p in paths:
            self._read_file(p, None)
        return PreprocessResult("\n".join(self.out) + "\n", self.line_map, self.sources, self.files,
                                self.key_comments)

    def _load(self, path: str, shown: str, at: SourceLoc | None) -> str | None:
        where = at or SourceLoc(shown, 1, 1)
        try:
            if os.path.isdir(path):
                self.sink.error("RG0001", f"'{shown}' is a directory, not an IDL file", where)
                return None
            with open(path, "rb") as fh:  # read at most one byte past the limit (devices report size 0)
                data = fh.read(MAX_INPUT_BYTES + 1)
            if len(data) > MAX_INPUT_BYTES:
                self.sink.error("RG0005", f"'{shown}' is larger than {MAX_INPUT_BYTES // (1024 * 1024)} MiB",
                                SourceLoc(shown, 1, 1), "split it, or check that it is the right file")
                return None
        except OSError as exc:
            self.sink.error("RG0001", f"cannot read '{shown}': {exc.strerror or exc}", where)
            return None
        nul = data.find(b"\0")
        if nul >= 0:
            line = data.count(b"\n", 0, nul) + 1
            col = nul - (data.rfind(b"\n", 0, nul) + 1) + 1
            self.sink.error("RG0002", "file contains a NUL byte; is it a binary file?",
                            SourceLoc(shown, line, col, line, col + 1),
                            "IDL sources must be UTF-8 text")
            return None
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as exc:
            line = data.count(b"\n", 0, exc.start) + 1
            # Columns count characters, as everywhere else (the line's start decodes fine).
            col = len(data[data.rfind(b"\n", 0, exc.start) + 1:exc.start].decode("utf-8")) + 1
            self.sink.error("RG0003", f"file is not valid UTF-8 (byte 0x{data[exc.start]:02x})",
                            SourceLoc(shown, line, col, line, col + 1),
                            "re-save the file as UTF-8")
            return None
        if text.startswith("\ufeff"):
            text = text[1:]
        return text

    def _read_file(self, path: str, at: SourceLoc | None) -> None:
        shown = display_path(path)
        real = os.path.realpath(path)
        if real in self._stack:
            chain = " -> ".join(display_path(p) for p in self._stack[self._stack.index(real):])
            self.sink.error("RG0102", f"include cycle: {chain} -> {shown}",
                            at or SourceLoc(shown, 1, 1),
                            "remove one of the #include lines or add an include guard")
            return
        if real in self._done:
            return
        if len(self._stack) >= MAX_INCLUDE_DEPTH:
            self.sink.error("RG0103", f"#include nested more than {MAX_INCLUDE_DEPTH} deep",
                            at or SourceLoc(shown, 1, 1))
            return
        text = self._load(path, shown, at)
        if text is None:
            return
        self._done.add(real)
        self.sources[shown] = text
        self.files.append(shown)
        self._stack.append(real)
        try:
            self._process(text, shown, os.path.dirname(path))
        finally:
            self._stack.pop()

    # -- lines -------------------------------------------------------------------
    def _emit(self, text: str, file: str, line: int) -> None:
        self.out.append(text)
        self.line_map.append((file, line))

    def _process(self, text: str, file: str, folder: str) -> None:
        lines = text.split("\n")
        if lines and lines[-1] == "":
            lines.pop()
        conds: list[_Cond] = []
        in_comment: SourceLoc | None = None
        i = 0
        while i < len(lines):
            raw = lines[i].rstrip("\r")
            lineno = i + 1
            i += 1
            active = not conds or conds[-1].active
            m = _DIRECTIVE.match(raw) if in_comment is None else None
            if m:
                # Directives continue over backslash-newline.
                body = raw
                while body.endswith("\\") and i < len(lines):
                    body = body[:-1] + " " + lines[i].rstrip("\r")
                    self._emit("", file, lineno)
                    i += 1
                m = _DIRECTIVE.match(body) or m
                name = m.group(1) or ""
                col = raw.index("#") + 1
                loc = SourceLoc(file, lineno, col, lineno, col + 1 + len(name))
                rest = _strip_comments(m.group(2)).strip()
                kept = self._directive(name, rest, loc, conds, active, folder, body)
                if kept is None:
                    self._emit("", file, lineno)
                elif kept:
                    self._emit(kept, file, lineno)
                continue
            in_comment, key_col = _scan_line(raw, in_comment, file, lineno)
            if active and key_col is not None:
                self.key_comments[(file, lineno)] = key_col
            if active:
                self._emit(self._expand(raw) if self._has_values() else raw, file, lineno)
            else:
                self._emit("", file, lineno)
        if in_comment is not None:
            self.sink.error("RG0108", "unterminated /* comment", in_comment,
                            "close the comment with */")
        for c in conds:
            self.sink.error("RG0104", "#if/#ifdef/#ifndef without a matching #endif", c.loc,
                            "add #endif at the end of the conditional block")

    def _has_values(self) -> bool:
        return any(v for v in self.macros.values())

    def _expand(self, line: str) -> str:
        """Replace object-like macros that have a value, outside strings and comments."""
        out: list[str] = []
        for seg, is_code in _segments(line):
            if is_code:
                seg = _IDENT.sub(lambda mm: self._macro_value(mm.group(0)), seg)
            out.append(seg)
        return "".join(out)

    def _macro_value(self, name: str, depth: int = 0) -> str:
        val = self.macros.get(name)
        if not val or depth > 32:
            return name
        return _IDENT.sub(lambda mm: self._macro_value(mm.group(0), depth + 1), val)

    # -- directives --------------------------------------------------------------
    def _directive(self, name: str, rest: str, loc: SourceLoc, conds: list[_Cond],
                   active: bool, folder: str, raw: str) -> str | None:
        """Handle one directive; returns a line to keep in the output, or None."""
        if name in ("if", "ifdef", "ifndef"):
            value = False
            if active:
                value = self._condition(name, rest, loc)
            conds.append(_Cond(active and value, value, active, loc))
            return None
        if name in ("elif", "else", "endif"):
            if not conds:
                self.sink.error("RG0104", f"#{name} without #if", loc,
                                "remove it or add the missing #if/#ifdef")
                return None
            top = conds[-1]
            if name == "endif":
                conds.pop()
            elif top.seen_else:
                self.sink.error("RG0104", f"#{name} after #else", loc)
            elif name == "else":
                top.seen_else = True
                top.active = top.parent_active and not top.taken
                top.taken = True
            else:
                value = top.parent_active and not top.taken and self._condition("if", rest, loc)
                top.active = value
                top.taken = top.taken or value
            return None
        if not active:
            return None
        if name == "define":
            m = _IDENT.match(rest)
            if not m:
                self.sink.error("RG0107", "#define needs a macro name", loc)
                return None
            after = rest[m.end():]
            if after.startswith("("):
                self.sink.error("RG0107", f"function-like macro '{m.group(0)}' is not supported",
                                loc, "IDL files only need object-like #define NAME [value]")
                return None
            self.macros[m.group(0)] = after.strip()
            return None
        if name == "undef":
            m = _IDENT.match(rest)
            if not m:
                self.sink.error("RG0107", "#undef needs a macro name", loc)
            else:
                self.macros.pop(m.group(0), None)
            return None
        if name == "include":
            self._include(rest, loc, folder)
            return None
        if name == "pragma":
            words = rest.split()
            if words and words[0] == "keylist":
                return raw  # parsed by the grammar, in its module scope
            self.sink.warning("RG0110", f"#pragma {words[0] if words else ''} ignored".rstrip(), loc)
            return None
        if name == "error":
            self.sink.error("RG0109", f"#error {rest}".rstrip(), loc)
            return None
        if name == "warning":
            self.sink.warning("RG0111", f"#warning {rest}".rstrip(), loc)
            return None
        if name == "line" or name == "":
            return None
        self.sink.error("RG0105", f"unknown preprocessor directive '#{name}'", loc,
                        "supported: #include #define #undef #if #ifdef #ifndef #elif #else "
                        "#endif #pragma #error #warning")
        return None

    def _include(self, rest: str, loc: SourceLoc, folder: str) -> None:
        m = re.match(r'^"([^"]+)"|^<([^>]+)>', rest)
        if not m:
            self.sink.error("RG0107", "#include expects \"file\" or <file>", loc)
            return
        target = m.group(1) or m.group(2)
        quoted = m.group(1) is not None
        search = ([folder or "."] if quoted else []) + self.include_dirs + ([] if quoted else [folder or "."])
        for d in search:
            cand = os.path.join(d, target)
            if os.path.isfile(cand):
                self._read_file(cand, loc)
                return
        where = ", ".join(display_path(d) for d in search) or "(none)"
        self.sink.error("RG0101", f"cannot find include file '{target}'", loc,
                        f"searched: {where}; add its folder with -I DIR")

    def _condition(self, kind: str, rest: str, loc: SourceLoc) -> bool:
        if kind in ("ifdef", "ifndef"):
            m = _IDENT.match(rest)
            if not m:
                self.sink.error("RG0107", f"#{kind} needs a macro name", loc)
                return False
            return (m.group(0) in self.macros) == (kind == "ifdef")
        try:
            return bool(evaluate_condition(rest, self.macros))
        except (ValueError, SyntaxError, ZeroDivisionError, RecursionError) as exc:
            self.sink.error("RG0106", f"cannot evaluate #if expression: {exc}", loc,
                            "use defined(NAME), integers and C operators")
            return False


def _segments(line: str):
    """Split a line into (text, is_code) pieces; strings and comments are not code."""
    i, start, n = 0, 0, len(line)
    while i < n:
        c = line[i]
        if c in "\"'":
            if i > start:
                yield line[start:i], True
            j = i + 1
            while j < n and line[j] != c:
                j += 2 if line[j] == "\\" else 1
            yield line[i:j + 1], False
            i = start = j + 1
        elif line.startswith("//", i) or line.startswith("/*", i):
            if i > start:
                yield line[start:i], True
            yield line[i:], False  # rest of the line: macros in comments are never expanded
            return
        else:
            i += 1
    if start < n:
        yield line[start:], True


_INTERESTING = re.compile(r'["\']|//|/\*')
_KEY_DIRECTIVE = re.compile(r"//\s*@key\b")


def _scan_line(line: str, in_comment: SourceLoc | None, file: str, lineno: int):
    """Track block-comment state across a line and find a trailing `//@key` directive.

    Returns (comment state after the line, 1-based column of a `//@key` comment or None).
    Jumps between quotes and comment markers with a regex: most lines have none.
    """
    i, n = 0, len(line)
    while i < n:
        if in_comment is not None:
            j = line.find("*/", i)
            if j < 0:
                return in_comment, None
            in_comment, i = None, j + 2
            continue
        m = _INTERESTING.search(line, i)
        if m is None:
            return None, None
        i = m.start()
        tok = m.group(0)
        if tok == "//":
            return None, (i + 1 if _KEY_DIRECTIVE.match(line, i) else None)
        if tok == "/*":
            in_comment = SourceLoc(file, lineno, i + 1, lineno, i + 3)
            i += 2
            continue
        j = i + 1  # a string or char literal: skip to its closing quote
        while j < n and line[j] != tok:
            j += 2 if line[j] == "\\" else 1
        i = j + 1
    return in_comment, None


def _strip_comments(text: str) -> str:
    text = re.sub(r"/\*.*?\*/", " ", text)
    return text.split("//", 1)[0]


def preprocess(paths: list[str], include_dirs: list[str], sink: DiagnosticSink,
               defines: dict[str, str] | None = None) -> PreprocessResult:
    return Preprocessor(include_dirs, sink, defines).run(paths)
