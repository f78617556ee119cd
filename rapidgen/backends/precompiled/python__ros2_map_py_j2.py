# mypy: ignore-errors
# Template templates/python/ros2_map.py.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "577f6f93128aca6ef70fb1355bb128739ce734ef77bbc578639057d3d0fe5d29"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'ros2_map.py.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_header = resolve('header')
    l_0_asset = resolve('asset')
    l_0_body = resolve('body')
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
    pass
    yield '# '
    yield str(t_1((undefined(name='header') if l_0_header is missing else l_0_header)))
    yield '\n"""Asset '
    yield str(t_2((undefined(name='asset') if l_0_asset is missing else l_0_asset)))
    yield ' mapped onto ROS 2, as data (the descriptor\'s ros2: section).\n\nNODE       the ROS 2 node name\nTELEMETRY  ROS 2 topic -> RAPID telemetry entry: topic, message type, kind and index of the\n           entry fed, its rate, and per kind the joint names (JointConfig order), the pose\n           and twist field paths and encodings, or (agent) [value key, field path, conversion,\n           scale] (conversion "yaw": a quaternion\'s heading)\nCOMMANDS   "Subsystem/command" -> publish: topic, message type, [field path, conversion,\n           references or constant], header stamped; until: topic, type, field, value,\n           timeout [s] or None. A reference is a parameter\'s index (the whole argument) or\n           [index, element or None, scale]; "quat_euler" takes [roll, pitch, yaw] references\n           (None: 0)\nSTREAMS    RAPID input stream -> ROS 2: the stream\'s name, RAPID type, topic, the writer\'s\n           partition, deadline [ms], on_loss, subsystem, state and missed value keys; ros2:\n           topic, message type, where the pose sits (or the joint names), frame, rot encoding,\n           stamped; stop: the message published on a loss with on_loss stop (or None)\nGROUND     RAPID -> ROS 2 (None without ros2.ground): the node name, and per joint, position\n           and agent entry (kind, index) the ROS 2 topic, joint names, frame and pose\n           encoding, or [value key, DataType, unit, warning, critical] ([below, above])\n"""\n\n'
    yield str((undefined(name='body') if l_0_body is missing else l_0_body))
    yield '\n'

blocks = {}
debug_info = '1=27&2=29&23=31'
