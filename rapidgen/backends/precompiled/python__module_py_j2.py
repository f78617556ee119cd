# mypy: ignore-errors
# Template templates/python/module.py.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "cebf93190f56fb2343dba3f15d5993ff26af86d6ac43e4d1b31bed24f17cc08a"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'module.py.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_f = resolve('f')
    l_0_m = missing
    try:
        t_1 = environment.filters['comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'comment' found.")
    try:
        t_2 = environment.filters['docstring']
    except KeyError:
        @internalcode
        def t_2(*unused):
            raise TemplateRuntimeError("No filter named 'docstring' found.")
    try:
        t_3 = environment.filters['py_str']
    except KeyError:
        @internalcode
        def t_3(*unused):
            raise TemplateRuntimeError("No filter named 'py_str' found.")
    pass
    l_0_m = context.vars['m'] = environment.get_template('_macros.j2', 'module.py.j2')._get_default_module(context)
    context.exported_vars.discard('m')
    yield '# '
    yield str(t_1(environment.getattr((undefined(name='f') if l_0_f is missing else l_0_f), 'header')))
    yield '\n"""'
    yield str(t_2(environment.getattr((undefined(name='f') if l_0_f is missing else l_0_f), 'doc')))
    yield '"""\n'
    for l_1_group in environment.getattr((undefined(name='f') if l_0_f is missing else l_0_f), 'import_groups'):
        _loop_vars = {}
        pass
        yield '\n'
        for l_2_line in l_1_group:
            _loop_vars = {}
            pass
            yield str(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'import_line'), l_2_line, _loop_vars=_loop_vars))
        l_2_line = missing
    l_1_group = missing
    for l_1_d in environment.getattr((undefined(name='f') if l_0_f is missing else l_0_f), 'decls'):
        _loop_vars = {}
        pass
        yield str(environment.getattr(l_1_d, 'lead'))
        yield str(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'declaration'), l_1_d, _loop_vars=_loop_vars))
    l_1_d = missing
    if environment.getattr((undefined(name='f') if l_0_f is missing else l_0_f), 'has_exports'):
        pass
        yield '\n__all__ = [\n'
        for l_1_name in environment.getattr((undefined(name='f') if l_0_f is missing else l_0_f), 'exports'):
            _loop_vars = {}
            pass
            yield '    '
            yield str(t_3(l_1_name))
            yield ',\n'
        l_1_name = missing
        yield ']\n'

blocks = {}
debug_info = '1=31&2=34&3=36&4=38&6=42&7=45&10=48&11=51&13=54&16=57&17=61'
