# mypy: ignore-errors
# Template templates/cpp/bridge/tables.cpp.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "93163ae2fff687b091ca1f8f7bb67dd65027e8204a5b098ca6b64b95ada3959d"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge/tables.cpp.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_p = resolve('p')
    l_0_v = resolve('v')
    try:
        t_1 = environment.filters['cpp_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'cpp_comment' found.")
    pass
    yield '// '
    yield str(t_1(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'header')))
    yield '\n// Asset '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'asset'))
    yield ' as the runtime\'s tables: subsystems, the command dictionary (units,\n// ranges, allowed values, defaults; in the order arguments are sent), the allow-list and\n// the telemetry entries. Literals only: the behaviour is rapid_runtime\'s.\n#include <cstdint>\n#include <limits>\n#include <optional>\n#include <string>\n\n#include "handlers.hpp"\n\nnamespace '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield ' {\n\nnamespace {\n\n::rapid_runtime::Tables build() {\n    ::rapid_runtime::Tables t;\n'
    for l_1_line in environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'tables'):
        _loop_vars = {}
        pass
        yield '    '
        yield str(l_1_line)
        yield '\n'
    l_1_line = missing
    yield '    return t;\n}\n\n}  // namespace\n\nconst ::rapid_runtime::Tables& tables() {\n    static const ::rapid_runtime::Tables built = build();\n    return built;\n}\n\n}  // namespace '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield '\n'

blocks = {}
debug_info = '1=20&2=22&12=24&18=26&19=30&31=34'
