# mypy: ignore-errors
# Template templates/python/ros2_ground.py.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "0d1403b80df353bfdf308b85509b6b016fbcbaf256776beb7a0407ba60621c44"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'ros2_ground.py.j2'

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
    yield '\n"""Asset '
    yield str(t_2((undefined(name='asset') if l_0_asset is missing else l_0_asset)))
    yield ' seen from ROS 2: `python -m '
    yield str((undefined(name='package') if l_0_package is missing else l_0_package))
    yield '.ros2_ground --help`.\n\nRepublishes the asset\'s RAPID telemetry and configs as standard ROS 2 messages, as\nros2_map.GROUND says; the code is rapid_runtime.ros2.ground (docs/ros2.md).\n"""\n\nimport sys\n\nfrom rapid_runtime.ros2.ground import main\n\nfrom . import asset_tables, rapid, ros2_map\n\nif __name__ == "__main__":\n    sys.exit(main(asset_tables, rapid, ros2_map, package='
    yield str(t_3((undefined(name='package') if l_0_package is missing else l_0_package)))
    yield '))\n'

blocks = {}
debug_info = '1=33&2=35&15=39'
