# mypy: ignore-errors
# Template templates/python/_support.py.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "86859136f2f84e43a0b4ac33b64a080abbef6e0f120a91dec3ad3f8c9ea36d8e"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = '_support.py.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_header = resolve('header')
    try:
        t_1 = environment.filters['comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'comment' found.")
    pass
    yield '# '
    yield str(t_1((undefined(name='header') if l_0_header is missing else l_0_header)))
    yield '\n"""Helpers the generated modules use: rapid_runtime.idl_support\'s, one copy for every package."""\n\nfrom rapid_runtime.idl_support import DeserializeError, checked, sequence\n\n__all__ = ["DeserializeError", "checked", "sequence"]\n'

blocks = {}
debug_info = '1=19'
