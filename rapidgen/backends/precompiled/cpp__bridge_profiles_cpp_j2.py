# mypy: ignore-errors
# Template templates/cpp/bridge/profiles.cpp.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "fe7b54fb64338de2bc2723202b93743e10dcb438d843222eed2aecca1a7cd0ca"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge/profiles.cpp.j2'

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
    yield '\n// The Fast DDS profiles of asset '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'asset'))
    yield ' (the qos target\'s fastdds/rapid_qos_profiles.xml),\n// built into the bridge: participants rapid_local (loopback only, the default), rapid_lan,\n// rapid_wan...; writer and reader profiles per RAPID QoS. --qos FILE replaces them.\n#include <string_view>\n\n#include "handlers.hpp"\n\nnamespace '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield ' {\n\nconst ::std::string_view PROFILES_XML =\n    "" /* the profiles: rapidgen embeds the qos target\'s XML here */;\n\n}  // namespace '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield '\n'

blocks = {}
debug_info = '1=20&2=22&9=24&14=26'
