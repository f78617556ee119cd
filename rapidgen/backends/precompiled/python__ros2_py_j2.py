# mypy: ignore-errors
# Template templates/python/ros2.py.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "e551b45632a934e6f1ab0e01b707fc8bc4f5dabc95ff6361c16bfe202c3feb0f"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'ros2.py.j2'

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
    yield ' served from a ROS 2 robot: `python -m '
    yield str((undefined(name='package') if l_0_package is missing else l_0_package))
    yield '.ros2 --help`.\n\nThe rapid_runtime bridge with handlers that act on ROS 2 and telemetry fed from ROS 2, as\nros2_map.py (the descriptor\'s ros2: section) says; the code is rapid_runtime.ros2.handlers\n(docs/ros2.md). rclpy, an RMW and the message packages are imported when it starts.\n"""\n\nimport sys\n\nfrom rapid_runtime.ros2.handlers import main\n\nfrom . import asset_tables, rapid, ros2_map\n\nif __name__ == "__main__":\n    sys.exit(main(asset_tables, rapid, ros2_map, package='
    yield str(t_3((undefined(name='package') if l_0_package is missing else l_0_package)))
    yield '))\n'

blocks = {}
debug_info = '1=33&2=35&16=39'
