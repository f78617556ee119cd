# mypy: ignore-errors
# Template templates/rust/bridge/transports.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "8d7fb34c491b71ced94b3ea3fe17832ac623586a9b054d79d94325013ec0e4d5"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge/transports.rs.j2'

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
    yield "\n//! Cyclone DDS configurations, one per transport (the qos target's cyclonedds/<transport>.xml):\n//! `--transport NAME` when CYCLONEDDS_URI is not set; `local` (loopback only) by default.\n//! Empty when generated without the qos target (Cyclone's defaults then).\n"
    for (l_1_plain, l_1_name, l_1_const) in environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'transports'):
        _loop_vars = {}
        pass
        yield '\npub const '
        yield str(l_1_const)
        yield ': &str = ""; // rapidgen embeds cyclonedds/'
        yield str(l_1_plain)
        yield '.xml here\n'
    l_1_plain = l_1_name = l_1_const = missing
    yield '\npub const ALL: &[(&str, &str)] = &['
    l_1_loop = missing
    for (l_1_plain, l_1_name, l_1_const), l_1_loop in LoopContext(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'transports'), undefined):
        _loop_vars = {}
        pass
        yield '('
        yield str(l_1_name)
        yield ', '
        yield str(l_1_const)
        yield ')'
        yield str((', ' if (not environment.getattr(l_1_loop, 'last')) else cond_expr_undefined("the inline if-expression on line 10 in 'bridge/transports.rs.j2' evaluated to false and no else section was defined.")))
    l_1_loop = l_1_plain = l_1_name = l_1_const = missing
    yield '];\n'

blocks = {}
debug_info = '1=20&5=22&7=26&10=33'
