# mypy: ignore-errors
# Template templates/rust/bridge/cmd.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "82c514595a3ea8a91b649b77120ac6487a32c278b8688a954a2b653e8b396037"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge/cmd.rs.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_c = resolve('c')
    l_0_v = resolve('v')
    try:
        t_1 = environment.filters['rust_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'rust_comment' found.")
    pass
    yield '// '
    yield str(t_1(environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'header')))
    yield '\n//! `'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'cmd'))
    yield ' [options] SUBSYSTEM COMMAND [key=value ...]`: a command to asset\n//! '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'asset'))
    yield ', checked against its dictionary (its live CommandConfig, the built-in tables\n//! for units, ranges and defaults), its acks printed as they come; exit 0 on COMPLETED/OK,\n//! else 1 (rapid_dds::cmd; `--help` lists the options).\nmod tables;\nmod transports;\n\nuse rapid_dds::cmd::{self, CmdProgram};\n\nfn main() {\n    std::process::exit(cmd::main(CmdProgram { tables_json: tables::JSON, transports: transports::ALL }));\n}\n'

blocks = {}
debug_info = '1=20&2=22&3=24'
