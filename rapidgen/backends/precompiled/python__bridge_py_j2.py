# mypy: ignore-errors
# Template templates/python/bridge.py.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "f89840a78e15dd992cbdc4e3e6a969ecc173032a36fda5ba91e06b28d4aba559"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge.py.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_header = resolve('header')
    l_0_asset = resolve('asset')
    l_0_package = resolve('package')
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
    yield '# '
    yield str(t_1((undefined(name='header') if l_0_header is missing else l_0_header)))
    yield '\n"""The RAPID bridge of asset '
    yield str(t_2((undefined(name='asset') if l_0_asset is missing else l_0_asset)))
    yield ': `python -m '
    yield str((undefined(name='package') if l_0_package is missing else l_0_package))
    yield '.bridge --help`.\n\nServes the asset with the rapid_runtime library: publishes its configs, takes commands\nfrom rapid_command in its partition, answers acks, runs the handlers in\n'
    yield str((undefined(name='package') if l_0_package is missing else l_0_package))
    yield '/handlers.py (yours), or a simulated robot with --simulate.\n"""\n\nimport sys\n\nfrom rapid_runtime.bridge import main\n\nfrom . import asset_tables, rapid\n\n\ndef _handlers():\n    from .handlers import Handlers\n    return Handlers()\n\n\nif __name__ == "__main__":\n    sys.exit(main(asset_tables, rapid, _handlers, package='
    yield str(t_3((undefined(name='package') if l_0_package is missing else l_0_package)))
    yield '))\n'

blocks = {}
debug_info = '1=33&2=35&6=39&22=41'
