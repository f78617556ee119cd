# mypy: ignore-errors
# Template templates/rust/bridge/tables.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "5d81b829573cb3b182e7fb61cc35d0aa37ffc968e318dd4ccc2c81b2a6200003"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge/tables.rs.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_c = resolve('c')
    l_0_tables_json = resolve('tables_json')
    try:
        t_1 = environment.filters['rust_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'rust_comment' found.")
    try:
        t_2 = environment.filters['rust_str']
    except KeyError:
        @internalcode
        def t_2(*unused):
            raise TemplateRuntimeError("No filter named 'rust_str' found.")
    pass
    yield '// '
    yield str(t_1(environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'header')))
    yield "\n//! The asset's tables as JSON (the command dictionary with units, ranges, allowed values and\n//! defaults, the allow-list, telemetry entries, publications), read by rapid_dds at start.\n\npub const JSON: &str = "
    yield str(t_2((undefined(name='tables_json') if l_0_tables_json is missing else l_0_tables_json)))
    yield ';\n'

blocks = {}
debug_info = '1=26&5=28'
