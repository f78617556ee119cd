# mypy: ignore-errors
# Template templates/rust/module.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "99dcec77d0fbc582578048bf7811ec3e80cedbf498a79a7f23817a4aa6133bb8"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'module.rs.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_c = resolve('c')
    l_0_m = resolve('m')
    l_0_decls = missing
    try:
        t_1 = environment.filters['rust_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'rust_comment' found.")
    pass
    included_template = environment.get_template('_decls.rs.j2', 'module.rs.j2')._get_default_module(context)
    l_0_decls = getattr(included_template, 'decls', missing)
    if l_0_decls is missing:
        l_0_decls = undefined(f"the template {included_template.__name__!r} (imported on line 1 in 'module.rs.j2') does not export the requested name 'decls'", name='decls')
    context.vars['decls'] = l_0_decls
    context.exported_vars.discard('decls')
    yield '// '
    yield str(t_1(environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'header')))
    yield '\n//! '
    yield str(t_1(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'doc')))
    yield ': Rust types with XCDR1 encode/decode (docs/rust-backend.md).\n'
    yield str(context.call((undefined(name='decls') if l_0_decls is missing else l_0_decls), (undefined(name='m') if l_0_m is missing else l_0_m)))
    yield '\n'

blocks = {}
debug_info = '1=20&2=27&3=29&4=31'
