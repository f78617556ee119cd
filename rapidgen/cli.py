"""Command line: argument handling only; the work lives in the pipeline modules.

Exit codes: 0 success, 1 errors in the input (diagnostics on stderr), 2 usage errors,
3 an internal error (a bug: please report it).
"""
from __future__ import annotations

import argparse
import functools
import os
import sys
from typing import Sequence

from rapidgen import __version__, backends, codes
from rapidgen.diagnostics import DiagnosticSink
from rapidgen.reporting import report


def _common_idl_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("-I", dest="include", action="append", default=[], metavar="DIR",
                   help="add DIR to the #include search path (repeatable)")
    p.add_argument("-D", dest="define", action="append", default=[], metavar="NAME[=VALUE]",
                   help="define a preprocessor macro (repeatable)")


def _warn_value(text: str) -> str:
    """One -W value: 'error', or 'no-CODE' for a registered code that can be a warning
    (silencing an error, a note or a misspelt code would silently do nothing)."""
    if text == "error":
        return text
    if not text.startswith("no-"):
        raise argparse.ArgumentTypeError(f"unknown value '{text}'; expected no-CODE (e.g. no-RG0501) or error")
    code = text[3:].upper()
    entry = codes.REGISTRY.get(code)
    if entry is None:
        raise argparse.ArgumentTypeError(f"unknown diagnostic code '{text[3:]}' (docs/idl-frontend.md lists them)")
    if not entry.allows("warning"):
        raise argparse.ArgumentTypeError(f"{code} is {'a note' if entry.severity == 'note' else 'an error'}; "
                                         "only warnings can be silenced")
    return f"no-{code}"


def _diag_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("-W", dest="warn", action="append", default=[], metavar="no-CODE|error", type=_warn_value,
                   help="-W no-RG0501 silences a warning code; -W error turns warnings into errors "
                   "(an unknown code, or a code that is never a warning, is a usage error)")
    p.add_argument("--format", default="text", choices=("text", "github"),
                   help="diagnostics as text (default) or as GitHub Actions annotations on stdout "
                   "(::error file=...,line=...::..., docs/ci.md)")


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The whole command line, or (only=NAME) the top level with NAME's subcommand alone:
    a run builds just the parser it uses, so `generate` never imports the live tools."""
    parser = argparse.ArgumentParser(prog="rapidgen", description=(
        "Compile RAPID IDL and asset descriptors into DDS bindings; check assets against the protocol."),
        epilog=f"targets (generate --lang): {', '.join(backends.known())}. "
        "Exit status: 0 success, 1 errors in the input, 2 usage error, 3 internal error.")
    parser.add_argument("--version", action="version", version=f"rapidgen {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for name, (add, _run) in SUBCOMMANDS.items():
        if only is None or name == only:
            add(sub)
    return parser


# -- each subcommand's arguments -------------------------------------------------------------
def _add_ir(sub) -> None:
    ir_p = sub.add_parser("ir", help="print the resolved model of IDL files as JSON")
    ir_p.add_argument("files", nargs="+", metavar="FILE", help="IDL files")
    _common_idl_args(ir_p)
    _diag_args(ir_p)
    ir_p.add_argument("--no-loc", action="store_true", help="omit source locations from the JSON")
    ir_p.add_argument("-o", "--output", metavar="FILE", help="write the JSON to FILE instead of stdout")


def _add_generate(sub) -> None:
    gen_p = sub.add_parser("generate", help="generate bindings from an asset descriptor or IDL files")
    gen_p.add_argument("inputs", nargs="+", metavar="ASSET.yaml|FILE.idl")
    _common_idl_args(gen_p)
    _diag_args(gen_p)
    gen_p.add_argument("--lang", default="python", metavar="LANG[,LANG...]",
                       help=f"targets to generate, comma-separated: {', '.join(backends.known())} "
                       "(default: python)")
    gen_p.add_argument("-o", "--output", required=True, metavar="DIR", help="output folder")
    gen_p.add_argument("--package", metavar="NAME", help="name of the generated Python package (default: "
                       "rapid_<asset name> for an asset, rapid_types for IDL alone)")


def _add_check(sub) -> None:
    chk_p = sub.add_parser("check", help="regenerate the project's targets in memory and report stale output")
    chk_p.add_argument("--project", default="rapidgen.yaml", metavar="FILE", help="project file (default: rapidgen.yaml)")
    chk_p.add_argument("--fix", action="store_true", help="rewrite stale output instead of failing")
    _diag_args(chk_p)


def _add_summary(sub) -> None:
    sum_p = sub.add_parser("summary", help="parse IDL files and print a one-line-per-module summary")
    sum_p.add_argument("files", nargs="+", metavar="FILE")
    _common_idl_args(sum_p)
    _diag_args(sum_p)


def _add_validate(sub) -> None:
    val_p = sub.add_parser("validate", help="check asset descriptors against the schema and the RAPID IDL")
    val_p.add_argument("files", nargs="+", metavar="ASSET.yaml")
    val_p.add_argument("--rapid", metavar="DIR", help="folder of the RAPID base IDL (default: the "
                       "descriptor's idl.rapid, else the nearest specs/rapid above it)")
    _diag_args(val_p)


def _add_describe(sub) -> None:
    desc_p = sub.add_parser("describe", help="print an asset's subsystems, command dictionary and telemetry")
    desc_p.add_argument("file", metavar="ASSET.yaml")
    desc_p.add_argument("--rapid", metavar="DIR", help="folder of the RAPID base IDL")
    desc_p.add_argument("--json", action="store_true", help="print the same content as JSON")
    _diag_args(desc_p)


def _add_init(sub) -> None:
    init_p = sub.add_parser("init", help="write a commented starter asset descriptor (never overwrites)")
    init_p.add_argument("name", nargs="?", default="MyRover", metavar="NAME", help="asset name (default MyRover)")
    init_p.add_argument("-o", "--output", metavar="FILE", help="the file to write (default: <name>.yaml)")


def _add_vectors(sub) -> None:
    vec_p = sub.add_parser("vectors", help="write golden CDR vectors (sample values and their XCDR1/XCDR2 bytes)")
    vec_p.add_argument("inputs", nargs="+", metavar="ASSET.yaml|FILE.idl")
    _common_idl_args(vec_p)
    _diag_args(vec_p)
    vec_p.add_argument("-o", "--output", required=True, metavar="FILE", help="the JSON file to write")


def _add_diff(sub) -> None:
    diff_p = sub.add_parser("diff", help="report wire, protocol and source breaking changes between two versions")
    diff_p.add_argument("paths", nargs="+", metavar="PATH", help="OLD NEW (IDL files, folders of IDL or asset "
                        "descriptors), or one PATH with --against REV")
    diff_p.add_argument("--against", metavar="REV", help="compare PATH with its version at git revision REV")
    _common_idl_args(diff_p)
    _diag_args(diff_p)
    diff_p.add_argument("--json", action="store_true", help="print the findings as JSON")
    diff_p.add_argument("--fail-on", default="", metavar="CAT[,CAT...]",
                        help="exit 1 when a change of these categories is found: WIRE, PROTOCOL, SOURCE")
    diff_p.add_argument("--ignore", action="append", default=[], metavar="RULE-ID", help="do not report a rule (repeatable)")
    diff_p.add_argument("--waivers", metavar="FILE", help="accepted changes per rule and type (docs/diff.md)")


def _add_cmd(sub) -> None:
    from rapidgen.cmd.command import add_parser
    add_parser(sub)


def _add_conform(sub) -> None:
    from rapidgen.conform.command import add_parser
    add_parser(sub)


def _add_spy(sub) -> None:
    from rapidgen.spy.command import add_parser
    add_parser(sub)


def _sink(args: argparse.Namespace) -> DiagnosticSink:
    silenced = frozenset(w[3:] for w in args.warn if w.startswith("no-"))
    return DiagnosticSink(silenced=silenced, warnings_as_errors="error" in args.warn)


def _report(args: argparse.Namespace):
    """report() in the format the command line asks for (--format)."""
    fmt = getattr(args, "format", "text")
    return report if fmt == "text" else functools.partial(report, fmt=fmt)


def _defines(items: list[str]) -> dict[str, str]:
    out = {}
    for item in items:
        name, _, value = item.partition("=")
        out[name] = value
    return out


def _cmd_ir(args: argparse.Namespace) -> int:
    from rapidgen.idl.load import load_idl
    from rapidgen.model.to_json import model_to_json

    sink = _sink(args)
    model, _ = load_idl(args.files, args.include, sink, _defines(args.define))
    _report(args)(sink)
    if model is None:
        return 1
    text = model_to_json(model, loc=not args.no_loc)
    if not args.output:
        sys.stdout.write(text)
        return 0
    from rapidgen.writer import write_output

    failed = DiagnosticSink()  # the diagnostics above are already printed
    if write_output(args.output, text, failed) is None:
        _report(args)(failed)
        return 1
    return 0


def _cmd_summary(args: argparse.Namespace) -> int:
    from rapidgen.idl.load import load_idl

    sink = _sink(args)
    model, pre = load_idl(args.files, args.include, sink, _defines(args.define))
    _report(args)(sink)
    if model is None:
        return 1
    counts: dict[str, dict[str, int]] = {}
    for d in model.declarations:
        module = d.scoped_name.rsplit("::", 1)[0] if "::" in d.scoped_name else "(global)"
        counts.setdefault(module, {}).setdefault(d.kind, 0)
        counts[module][d.kind] += 1
    lines = sum(len(t.splitlines()) for t in pre.sources.values())
    print(f"{len(pre.files)} files, {lines} lines, {len(model.declarations)} declarations")
    for module in sorted(counts):
        kinds = ", ".join(f"{n} {k}{'s' * (n != 1)}" for k, n in sorted(counts[module].items()))
        print(f"  {module}: {kinds}")
    keyed = [d for d in model.declarations if getattr(d, "keys", ())]
    print(f"  keyed types: {len(keyed)}")
    return 0


def _cmd_validate(args: argparse.Namespace) -> int:
    from rapidgen.asset.describe import run_validate
    return run_validate(args.files, args.rapid, _sink(args), _report(args))


def _cmd_describe(args: argparse.Namespace) -> int:
    from rapidgen.asset.describe import run_describe
    return run_describe(args.file, args.rapid, _sink(args), _report(args), as_json=args.json)


def _cmd_init(args: argparse.Namespace) -> int:
    from rapidgen.asset.scaffold import run_init
    return run_init(args.name, args.output, DiagnosticSink(), report)


def _cmd_cmd(args: argparse.Namespace) -> int:
    from rapidgen.cmd.command import run_cmd
    return run_cmd(args, DiagnosticSink())


def _cmd_generate(args: argparse.Namespace) -> int:
    from rapidgen.generate import generate_command

    langs, problem = backends.parse_langs(args.lang)
    if problem:
        print(f"rapidgen generate: --lang: {problem}", file=sys.stderr)
        return 2
    sink = _sink(args)
    ok = generate_command(args.inputs, args.include, _defines(args.define), langs, args.output, args.package, sink)
    _report(args)(sink)
    return 0 if ok else 1


def _cmd_check(args: argparse.Namespace) -> int:
    from rapidgen.generate import check_command

    sink = _sink(args)
    code = check_command(args.project, args.fix, sink, annotate=args.format == "github")
    _report(args)(sink)
    return code


def _cmd_vectors(args: argparse.Namespace) -> int:
    from rapidgen.vectors import run_vectors
    return run_vectors(args.inputs, args.include, args.output, _sink(args), _report(args), _defines(args.define))


def _cmd_conform(args: argparse.Namespace) -> int:
    from rapidgen.conform.command import run_conform
    return run_conform(args, DiagnosticSink(), report)


def _cmd_spy(args: argparse.Namespace) -> int:
    from rapidgen.spy.command import run_spy
    return run_spy(args, DiagnosticSink(), report)


def _cmd_diff(args: argparse.Namespace) -> int:
    from rapidgen.diff.command import run_diff
    return run_diff(args, _sink(args), _report(args))


# Every subcommand registers the same way: name -> (its arguments, its run), in help order.
# The live tools (cmd, conform, spy) keep their arguments beside their code.
SUBCOMMANDS = {
    "ir": (_add_ir, _cmd_ir), "generate": (_add_generate, _cmd_generate), "check": (_add_check, _cmd_check),
    "summary": (_add_summary, _cmd_summary), "validate": (_add_validate, _cmd_validate),
    "describe": (_add_describe, _cmd_describe), "init": (_add_init, _cmd_init), "cmd": (_add_cmd, _cmd_cmd),
    "vectors": (_add_vectors, _cmd_vectors), "diff": (_add_diff, _cmd_diff),
    "conform": (_add_conform, _cmd_conform), "spy": (_add_spy, _cmd_spy),
}


# Tools that live in their own package: the module has add_parser(sub) and run(args) -> int
# and is imported only when its command runs (or for the whole --help).
_TOOL_MODULES = {
    "secure": "rapidgen.secure.command", "record": "rapidgen.record.command",
    "replay": "rapidgen.record.replay_command", "monitor": "rapidgen.monitor.command",
}


def _tool(module: str):
    import importlib

    def add(sub) -> None:
        importlib.import_module(module).add_parser(sub)

    def run(args: argparse.Namespace) -> int:
        return int(importlib.import_module(module).run(args))
    return add, run


SUBCOMMANDS.update({name: _tool(mod) for name, mod in _TOOL_MODULES.items()})


def _command_of(argv: Sequence[str]) -> str | None:
    """The subcommand a command line names, when its first word is one (else None: the
    whole parser then reports usage, help or the version)."""
    return argv[0] if argv and argv[0] in SUBCOMMANDS else None


# Commands that hold nothing outside the process (no DDS participant, no temporary folder
# left open) once they return: a process that runs one of them ends without freeing its
# objects one by one (_hard_exit), as mypy does; freeing a large model took ~0.1 s.
_QUICK_EXIT = frozenset({"ir", "generate", "check", "summary", "validate", "describe", "vectors", "diff"})
# Of those, the ones that pause the cyclic GC for their work (their model holds no cycles):
# as a whole process they keep it paused to the end. Turning it back on would start a
# collection of everything allocated meanwhile, all still in the youngest generation
# (~14 ms at 100 structs, more the larger the model), only for the process to end.
_NO_CYCLIC_GC = frozenset({"ir", "generate", "check"})


def _hard_exit(code: int) -> None:
    from rapidgen import codecache

    codecache.save()
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except (BrokenPipeError, ValueError):  # a reader gone, or a stream closed: nothing left to say
        pass
    os._exit(code)


def main(argv: Sequence[str] | None = None) -> int:
    """The command line; `argv` None: this process's own (the console script and `python -m
    rapidgen`), and then a compiler command ends the process itself when done."""
    whole_process = argv is None
    argv = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser(only=_command_of(argv))
    args = parser.parse_args(argv)
    if whole_process and args.command in _NO_CYCLIC_GC:
        import gc
        gc.disable()
    code = _run(args)
    if whole_process and args.command in _QUICK_EXIT:
        _hard_exit(code)
    return code


def _run(args: argparse.Namespace) -> int:
    try:
        return SUBCOMMANDS[args.command][1](args)
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        return 0
    except Exception as exc:  # a bug: report it briefly; RAPIDGEN_DEBUG=1 shows the traceback
        if os.environ.get("RAPIDGEN_DEBUG"):
            raise
        print(f"rapidgen: internal error: {type(exc).__name__}: {exc}\n"
              "  please report this with the input; RAPIDGEN_DEBUG=1 shows the traceback", file=sys.stderr)
        return 3


if __name__ == "__main__":
    raise SystemExit(main())
