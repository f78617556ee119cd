# mypy: ignore-errors
# Template templates/cpp/bridge/main.cpp.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "f6a45a4a94e1140446f03ba1dfe088e871ab3066d19f3ba22b7db4631d54154a"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge/main.cpp.j2'

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
    yield '\n// The RAPID bridge of asset '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'asset'))
    yield ': `'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'package'))
    yield '_bridge --help`. Serves the asset with\n// the rapid_runtime_cpp library on Fast DDS: publishes its configs, takes commands from\n// rapid_command in its partition, answers acks, runs the handlers of handlers.cpp (yours),\n// or a simulated robot with --simulate.\n#include <memory>\n#include <vector>\n\n#include <rapid_runtime/dds/program.hpp>\n#include <'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'package'))
    yield '/asset.hpp>\n\n#include "handlers.hpp"\n\nnamespace {\n\nvoid publish_configs(::rapid_runtime::dds::Bridge& bridge) {\n'
    t_2 = 1
    for l_1_c in environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'configs'):
        _loop_vars = {}
        pass
        yield '    bridge.publish_config('
        yield str(environment.getattr(l_1_c, 'topic'))
        yield ', ::'
        yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'package'))
        yield '::'
        yield str(environment.getattr(l_1_c, 'function'))
        yield '(), '
        yield str(environment.getattr(l_1_c, 'qos'))
        yield ');\n'
        t_2 = 0
    l_1_c = missing
    if t_2:
        pass
        yield '    (void)bridge;\n'
    yield "}\n\n// Extension telemetry of the simulated robot: plausible messages of the asset's own types.\n::std::vector<::rapid_runtime::dds::CustomPublisher> custom_publishers() {\n    ::std::vector<::rapid_runtime::dds::CustomPublisher> out;\n"
    for l_1_c in environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'custom'):
        _loop_vars = {}
        pass
        yield '    out.push_back({'
        yield str(environment.getattr(l_1_c, 'entry'))
        yield 'u, '
        yield str(environment.getattr(l_1_c, 'role'))
        yield ',\n        [](::rapid_runtime::dds::Bridge& bridge) { bridge.node().writer<'
        yield str(environment.getattr(l_1_c, 'type'))
        yield '>('
        yield str(environment.getattr(l_1_c, 'topic'))
        yield ', '
        yield str(environment.getattr(l_1_c, 'qos'))
        yield '); },\n        [](::rapid_runtime::dds::Bridge& bridge) {\n            '
        yield str(environment.getattr(l_1_c, 'type'))
        yield ' value = '
        yield str(environment.getattr(l_1_c, 'value'))
        yield ';\n'
        if (environment.getattr(l_1_c, 'is_config') and environment.getattr(l_1_c, 'has_hdr')):
            pass
            yield '            bridge.publish_config('
            yield str(environment.getattr(l_1_c, 'topic'))
            yield ', value, '
            yield str(environment.getattr(l_1_c, 'qos'))
            yield ');\n'
        elif environment.getattr(l_1_c, 'has_hdr'):
            pass
            yield '            bridge.publish('
            yield str(environment.getattr(l_1_c, 'topic'))
            yield ', value, '
            yield str(environment.getattr(l_1_c, 'config_topic'))
            yield ', '
            yield str(environment.getattr(l_1_c, 'qos'))
            yield ');\n'
        else:
            pass
            yield '            bridge.node().writer<'
            yield str(environment.getattr(l_1_c, 'type'))
            yield '>('
            yield str(environment.getattr(l_1_c, 'topic'))
            yield ', '
            yield str(environment.getattr(l_1_c, 'qos'))
            yield ')->write(&value);\n'
        yield '        }});\n'
    l_1_c = missing
    yield '    return out;\n}\n\n}  // namespace\n\nint main(int argc, char** argv) {\n    ::rapid_runtime::dds::Program program;\n    program.tables = &::'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield '::tables();\n    program.profiles_xml = ::'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield '::PROFILES_XML;\n    program.publish_configs = publish_configs;\n    program.make_handlers = [] {\n        return ::std::make_unique<::'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield '::Dispatch>(::'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield '::make_handlers());\n    };\n    program.custom = custom_publishers();\n'
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'):
        pass
        yield '    program.simulated_streams = ::'
        yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
        yield '::'
        yield str(environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'simulate'))
        yield ';\n'
    yield '    return ::rapid_runtime::dds::run_bridge(argc, argv, program);\n}\n'

blocks = {}
debug_info = '1=20&2=22&10=26&17=29&18=33&27=47&28=51&29=55&31=61&32=65&33=68&34=72&35=75&37=84&48=93&49=95&52=97&55=101&56=104'
