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

import bisect
import os
import re
from dataclasses import dataclass, field

from rapidgen.diagnostics import DiagnosticSink, SourceLoc, display_path
from rapidgen.idl.ifexpr import evaluate as evaluate_condition

# Per file, and for all files of one run together. The parser and resolver take ~80 bytes of
# memory and ~1.5 s per MiB of dense declarations: 16 MiB stays near 1.4 GB and 25 s.
MAX_INPUT_BYTES = 16 * 1024 * 1024
MAX_INPUT_FILES = 10_000  # files read in one run (each include-once file counts once)
MAX_INCLUDE_DEPTH = 64
MAX_DIRECTIVE_CHARS = 64 * 1024  # one directive, after joining its backslash-continued lines
# Object-like macros can double at each level (#define A1 A0+A0): without a cap, 22
# levels make a line of millions of characters. One use of a macro may expand to at most
# MAX_MACRO_EXPANSION characters, and all expansions together may add MAX_EXPANDED_TOTAL.
MAX_MACRO_EXPANSION = 64 * 1024
MAX_EXPANDED_TOTAL = 64 * 1024 * 1024
MAX_MACRO_DEPTH = 32  # a macro naming itself (directly or not) stops expanding here

_DIRECTIVE = re.compile(r"^\s*#\s*([A-Za-z_]\w*)?(.*)$")
# What a line needs looking at for: a directive's '#', a comment's '/', a literal's quote, a
# CR to strip. Lines with none of them are passed on as they are, many at once.
_NOT_PLAIN = re.compile("[#/\"'\r]")
_IDENT = re.compile(r"[A-Za-z_]\w*")


class LineMap:
    """Output line -> (file, line), stored as runs of consecutive lines (a list of one
    tuple per line cost ~100 bytes a line: gigabytes for a large file of short lines)."""

    def __init__(self) -> None:
        self.starts: list[int] = []  # 0-based output line where each run starts
        self.origins: list[tuple[str, int]] = []  # (file, line) of each run's first line
        self.count = 0  # output lines so far
        self._last = 0  # run of the last lookup

    def add(self, file: str, line: int, count: int = 1) -> None:
        if self.origins:
            f, ln = self.origins[-1]
            if f == file and ln + self.count - self.starts[-1] == line:  # continues the last run
                self.count += count
                return
        self.starts.append(self.count)
        self.origins.append((file, line))
        self.count += count

    def __len__(self) -> int:
        return self.count

    def __getitem__(self, index: int) -> tuple[str, int]:
        """(file, line) of a 0-based output line (negative counts from the end)."""
        if index < 0:
            index += self.count
        if not 0 <= index < self.count:
            raise IndexError(index)
        run = self._last  # tokens arrive in order: usually the run of the previous lookup
        if not (self.starts[run] <= index and (run + 1 == len(self.starts) or index < self.starts[run + 1])):
            run = self._last = bisect.bisect_right(self.starts, index) - 1
        f, ln = self.origins[run]
        return f, ln + index - self.starts[run]


@dataclass
class PreprocessResult:
    text: str
    line_map: LineMap
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
        self._valued = sum(1 for v in self.macros.values() if v)  # macros that expand to something
        self._expanded = 0  # characters added by macro expansion so far
        self._expansions: dict[str, str] = {}  # name -> its expansion, until the next #define/#undef
        self._bytes_read = 0
        self.out: list[str] = []
        self.line_map = LineMap()
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
            if len(self._done) >= MAX_INPUT_FILES:
                self.sink.error("RG0006", f"more than {MAX_INPUT_FILES} input files in one run", where,
                                "split the input into several runs")
                return None
            with open(path, "rb") as fh:  # read at most one byte past the limit (devices report size 0)
                data = fh.read(MAX_INPUT_BYTES + 1)
            if len(data) > MAX_INPUT_BYTES:
                self.sink.error("RG0005", f"'{shown}' is larger than {MAX_INPUT_BYTES // (1024 * 1024)} MiB",
                                SourceLoc(shown, 1, 1), "split it, or check that it is the right file")
                return None
            self._bytes_read += len(data)
            if self._bytes_read > MAX_INPUT_BYTES:
                self.sink.error("RG0005", f"the input files together are larger than "
                                f"{MAX_INPUT_BYTES // (1024 * 1024)} MiB (reading '{shown}')", where,
                                "split the input into several runs")
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
    def _emit(self, text: str, file: str, line: int, count: int = 1) -> None:
        """Append `count` output lines (text holds count - 1 newlines) from file:line onwards."""
        self.out.append(text)
        self.line_map.add(file, line, count)

    def _process(self, text: str, file: str, folder: str) -> None:
        # Walks the text line by line with find() rather than split(): lines inside a block
        # comment are passed on in one piece, so a huge comment costs no per-line objects.
        conds: list[_Cond] = []
        in_comment: SourceLoc | None = None
        pos, n, lineno = 0, len(text), 0
        while pos < n:
            active = not conds or conds[-1].active
            if in_comment is not None:
                close = text.find("*/", pos)
                stop = n if close < 0 else text.rfind("\n", pos, close) + 1  # the line holding */
                if stop > pos:  # whole lines inside the comment
                    chunk = text[pos:stop - 1] if text[stop - 1] == "\n" else text[pos:stop]
                    count = chunk.count("\n") + 1
                    self._emit(chunk if active else "\n" * (count - 1), file, lineno + 1, count)
                    lineno += count
                    pos = stop
                    continue
            if active and not self._valued:  # no macro to expand: plain lines go on in one piece
                special = _NOT_PLAIN.search(text, pos)
                stop = n if special is None else text.rfind("\n", pos, special.start()) + 1
                if stop > pos:  # whole lines with no directive, comment, literal or CR
                    chunk = text[pos:stop - 1] if text[stop - 1] == "\n" else text[pos:stop]
                    count = chunk.count("\n") + 1
                    self._emit(chunk, file, lineno + 1, count)
                    lineno += count
                    pos = stop
                    continue
            eol = text.find("\n", pos)
            if eol < 0:
                eol = n
            raw = text[pos:eol].rstrip("\r")
            pos = eol + 1
            lineno += 1
            m = _DIRECTIVE.match(raw) if in_comment is None else None
            if m:
                # Directives continue over backslash-newline.
                parts, size, last, first = [raw], len(raw), raw, lineno
                while last.endswith("\\") and pos < n:
                    eol = text.find("\n", pos)
                    if eol < 0:
                        eol = n
                    last = text[pos:eol].rstrip("\r")
                    pos = eol + 1
                    lineno += 1
                    size += len(last) + 1
                    if size <= MAX_DIRECTIVE_CHARS:
                        parts[-1] = parts[-1][:-1]
                        parts.append(last)
                    self._emit("", file, first)
                body = " ".join(parts)  # (joined once: repeated += is quadratic in the line count)
                m = _DIRECTIVE.match(body) or m
                name = m.group(1) or ""
                col = raw.index("#") + 1
                loc = SourceLoc(file, first, col, first, col + 1 + len(name))
                if size > MAX_DIRECTIVE_CHARS:
                    self.sink.error("RG0107", f"#{name} directive longer than {MAX_DIRECTIVE_CHARS} characters",
                                    loc, "directives hold short names and values")
                    self._emit("", file, first)
                    continue
                rest = _strip_comments(m.group(2)).strip()
                kept = self._directive(name, rest, loc, conds, active, folder, body)
                self._emit(kept or "", file, first)
                continue
            in_comment, key_col = _scan_line(raw, in_comment, file, lineno)
            if active and key_col is not None:
                self.key_comments[(file, lineno)] = key_col
            if active:
                self._emit(self._expand(raw, file, lineno) if self._valued else raw, file, lineno)
            else:
                self._emit("", file, lineno)
        if in_comment is not None:
            self.sink.error("RG0108", "unterminated /* comment", in_comment,
                            "close the comment with */")
        for c in conds:
            self.sink.error("RG0104", "#if/#ifdef/#ifndef without a matching #endif", c.loc,
                            "add #endif at the end of the conditional block")

    def _set_macro(self, name: str, value: str | None) -> None:
        """Define (value not None) or undefine a macro, keeping count of those with a value."""
        self._valued -= bool(self.macros.get(name))
        self._expansions.clear()
        if value is None:
            self.macros.pop(name, None)
        else:
            self.macros[name] = value
            self._valued += bool(value)

    def _expand(self, line: str, file: str, lineno: int) -> str:
        """Replace object-like macros that have a value, outside strings and comments."""
        out: list[str] = []
        for start, end, is_code in _segments(line):
            if not is_code:
                out.append(line[start:end])
                continue
            pos = start
            for mm in _IDENT.finditer(line, start, end):
                out.append(line[pos:mm.start()])
                out.append(self._use(mm.group(0), SourceLoc(file, lineno, mm.start() + 1, lineno, mm.end() + 1)))
                pos = mm.end()
            out.append(line[pos:end])
        return "".join(out)

    def _use(self, name: str, loc: SourceLoc) -> str:
        """The expansion of one use of a name in code, within the expansion limits."""
        if not self.macros.get(name) or self._expanded > MAX_EXPANDED_TOTAL:
            return name
        text = self._expansions.get(name)
        if text is None:
            try:
                text = self._expansions[name] = self._macro_value(name, 0, [MAX_MACRO_EXPANSION])
            except _TooLarge:
                self.sink.error("RG0113", f"macro '{name}' expands to more than {MAX_MACRO_EXPANSION} characters",
                                loc, "macros that use other macros more than once grow exponentially; "
                                "define the value directly")
                return name
        self._expanded += len(text)
        if self._expanded > MAX_EXPANDED_TOTAL:
            self.sink.error("RG0113", f"macro expansions add more than {MAX_EXPANDED_TOTAL // (1024 * 1024)} "
                            f"MiB to the input (here: '{name}')", loc, "use fewer or shorter macros")
            return name
        return text

    def _macro_value(self, name: str, depth: int, budget: list[int]) -> str:
        """The text a name expands to; raises _TooLarge once more than budget[0] characters."""
        val = self.macros.get(name)
        if not val or depth > MAX_MACRO_DEPTH:
            budget[0] -= len(name)
            if budget[0] < 0:
                raise _TooLarge
            return name
        parts: list[str] = []
        pos = 0
        for mm in _IDENT.finditer(val):
            parts.append(val[pos:mm.start()])
            budget[0] -= mm.start() - pos
            parts.append(self._macro_value(mm.group(0), depth + 1, budget))
            pos = mm.end()
        parts.append(val[pos:])
        budget[0] -= len(val) - pos
        if budget[0] < 0:
            raise _TooLarge
        return "".join(parts)

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
            self._set_macro(m.group(0), after.strip())
            return None
        if name == "undef":
            m = _IDENT.match(rest)
            if not m:
                self.sink.error("RG0107", "#undef needs a macro name", loc)
            else:
                self._set_macro(m.group(0), None)
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
        except RecursionError:
            self.sink.error("RG0106", "#if expression nested too deeply", loc)
            return False
        except (ValueError, SyntaxError, ZeroDivisionError) as exc:
            self.sink.error("RG0106", f"cannot evaluate #if expression: {exc}", loc,
                            "use defined(NAME), integers and C operators")
            return False


class _TooLarge(Exception):
    """A macro expansion went past MAX_MACRO_EXPANSION."""


_INTERESTING = re.compile(r'["\']|//|/\*')
_KEY_DIRECTIVE = re.compile(r"//\s*@key\b")
# A quoted literal up to its closing quote (or the end of the line, or a final backslash).
# Possessive repeats: linear time and no regex-engine state per character on long strings.
_QUOTED = {q: re.compile(q + r"(?:[^" + q + r"\\]++|\\.)*+[" + q + r"\\]?") for q in "\"'"}


def _quoted_end(line: str, i: int) -> int:
    """The end of the quoted literal that starts at line[i] (the pattern always matches)."""
    m = _QUOTED[line[i]].match(line, i)
    assert m is not None
    return m.end()


def _segments(line: str):
    """Split a line into (start, end, is_code) pieces; strings and comments are not code."""
    start, n = 0, len(line)
    while start < n:
        m = _INTERESTING.search(line, start)
        if m is None:
            break
        i = m.start()
        if i > start:
            yield start, i, True
        if m.group(0) in "\"'":
            j = _quoted_end(line, i)
            yield i, j, False
            start = j
        else:
            yield i, n, False  # rest of the line: macros in comments are never expanded
            return
    if start < n:
        yield start, n, True


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
        i = _quoted_end(line, i)  # a string or char literal: skip to its closing quote
    return in_comment, None


def _strip_comments(text: str) -> str:
    text = re.sub(r"/\*.*?\*/", " ", text)
    return text.split("//", 1)[0]


def preprocess(paths: list[str], include_dirs: list[str], sink: DiagnosticSink,
               defines: dict[str, str] | None = None) -> PreprocessResult:
    return Preprocessor(include_dirs, sink, defines).run(paths)
