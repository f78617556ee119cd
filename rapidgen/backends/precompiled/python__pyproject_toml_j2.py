# mypy: ignore-errors
# Template templates/python/pyproject.toml.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "b3200c74d48058b68f329f213c9b46f372c82fcc13486203f910b3c0e0d13d64"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'pyproject.toml.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_p = resolve('p')
    l_0_runtime = resolve('runtime')
    try:
        t_1 = environment.filters['comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'comment' found.")
    try:
        t_2 = environment.filters['join']
    except KeyError:
        @internalcode
        def t_2(*unused):
            raise TemplateRuntimeError("No filter named 'join' found.")
    try:
        t_3 = environment.filters['map']
    except KeyError:
        @internalcode
        def t_3(*unused):
            raise TemplateRuntimeError("No filter named 'map' found.")
    try:
        t_4 = environment.filters['toml_str']
    except KeyError:
        @internalcode
        def t_4(*unused):
            raise TemplateRuntimeError("No filter named 'toml_str' found.")
    pass
    yield '# '
    yield str(t_1(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'header')))
    yield '\n[build-system]\nrequires = ["setuptools>=61"]\nbuild-backend = "setuptools.build_meta"\n\n[project]\nname = '
    yield str(t_4(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'name')))
    yield '\nversion = '
    yield str(t_4(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'version')))
    yield '\ndescription = '
    yield str(t_4(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'description')))
    yield '\nrequires-python = ">=3.9"\ndependencies = ['
    yield str(t_2(context.eval_ctx, t_3(context, environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'requirements'), 'toml_str'), ', '))
    yield ']\n\n[tool.setuptools.packages.find]\ninclude = ['
    yield str(t_2(context.eval_ctx, t_3(context, environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'include'), 'toml_str'), ', '))
    yield ']\n'
    if (undefined(name='runtime') if l_0_runtime is missing else l_0_runtime):
        pass
        yield '\n# The QoS files travel inside the package: RapidQos() finds them after `pip install`.\n[tool.setuptools.package-data]\n'
        yield str(t_4(environment.getattr((undefined(name='runtime') if l_0_runtime is missing else l_0_runtime), 'package')))
        yield ' = ['
        yield str(t_2(context.eval_ctx, t_3(context, environment.getattr((undefined(name='runtime') if l_0_runtime is missing else l_0_runtime), 'package_data'), 'toml_str'), ', '))
        yield ']\n'

blocks = {}
debug_info = '1=38&7=40&8=42&9=44&11=46&14=48&15=50&19=53'
