# mypy: ignore-errors
# Template templates/python/qos.py.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "eaded78fa32b674aeecef3483dca63199a3120344fc6a60a526d1f3db9dda113"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'qos.py.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_q = resolve('q')
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
    yield str(t_1(environment.getattr((undefined(name='q') if l_0_q is missing else l_0_q), 'header')))
    yield '\n"""QoS per RAPID topic, exactly as the generated QoS files define it: rapid_runtime.qos with\nthis package\'s default folder (docs/python-backend.md, "QoS at run time").\n\n    from '
    yield str(t_2(environment.getattr((undefined(name='q') if l_0_q is missing else l_0_q), 'package')))
    yield ".qos import RapidQos\n\n    qos = RapidQos()              # the package's own qos_files/ (asset packages), else <out>/qos\n                                  # beside this package generated as <out>/python/"
    yield str(t_2(environment.getattr((undefined(name='q') if l_0_q is missing else l_0_q), 'package')))
    yield '\n    qos = RapidQos("out/qos")     # or a qos folder given explicitly\n"""\n\nimport os\n\nfrom rapid_runtime import qos as _qos\nfrom rapid_runtime.qos import QosFilesMissing, RapidQosError, UnknownTopic\n\n__all__ = ["QosFilesMissing", "RapidQos", "RapidQosError", "UnknownTopic", "default_qos_dir"]\n\n_HERE = os.path.dirname(os.path.abspath(__file__))\n\n\ndef default_qos_dir():\n    """This package\'s own `qos_files/`, else `<out>/qos` beside `<out>/python/<package>/`."""\n    return _qos.package_qos_dir(_HERE)\n\n\nclass RapidQos(_qos.RapidQos):\n    """rapid_runtime.qos.RapidQos, from `qos_dir` or this package\'s default folder."""\n\n    def __init__(self, qos_dir=None):\n        super().__init__(qos_dir, package_dir=_HERE)\n'

blocks = {}
debug_info = '1=25&5=27&8=29'
