# mypy: ignore-errors
# Template templates/cpp/Config.cmake.in.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "8494bd8864320f3e5290e9d291193ebc5828cdc2f28d85b1672e7546ec6ce5a2"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'Config.cmake.in.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_p = resolve('p')
    try:
        t_1 = environment.filters['cpp_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'cpp_comment' found.")
    pass
    yield '# '
    yield str(t_1(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'header')))
    yield '\n@PACKAGE_INIT@\ninclude(CMakeFindDependencyMacro)\nfind_dependency(fastcdr)\nfind_dependency(fastrtps)\ninclude("${CMAKE_CURRENT_LIST_DIR}/'
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield 'Targets.cmake")\ncheck_required_components('
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ')\n'

blocks = {}
debug_info = '1=19&6=21&7=23'
