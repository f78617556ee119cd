# mypy: ignore-errors
# Template templates/cpp/bridge/handlers.hpp.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "c73940c934695fa8a8cba02e5848e5c36a4318f3a9d88e176ceaf555e5ab88e9"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge/handlers.hpp.j2'

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
    yield '\n// The command handlers of asset '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'asset'))
    yield ": one abstract class per subsystem type, one\n// pure virtual method per command with its arguments by name and type (already checked\n// against the descriptor: types, ranges, allowed values). Implement them in handlers.cpp\n// (yours: rapidgen writes it once and never again) and return from make_handlers().\n//\n// A method runs on a thread of its own and may run long. Return Result::ok(text) for\n// COMPLETED/OK (text: Ack.message, cut to 127 bytes), Result::failed(why) (or throw\n// rapid_runtime::CommandFailed) for COMPLETED/EXEC_FAILED; ctx.progress(text) sends an\n// EXECUTING ack; stop early when ctx.cancelled() (ctx.sleep(s) returns false then) and\n// return Result::canceled(). ctx.subsystem() names the instance addressed (two subsystems\n// may share a type). The standard Admin, Queue and AccessControl commands are the runtime's.\n#ifndef "
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'guard'))
    yield '_BRIDGE_HANDLERS_HPP\n#define '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'guard'))
    yield '_BRIDGE_HANDLERS_HPP\n\n#include <array>\n#include <cstdint>\n#include <functional>\n#include <memory>\n#include <string>\n#include <string_view>\n\n#include <rapid_runtime/dds/bridge_handlers.hpp>\n#include <rapid_runtime/handlers.hpp>\n#include <rapid_runtime/tables.hpp>\n\nnamespace '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield " {\n\n// The asset as the runtime's tables (tables.cpp).\nconst ::rapid_runtime::Tables& tables();\n// The asset's Fast DDS profiles, built in (profiles.cpp).\nextern const ::std::string_view PROFILES_XML;\n"
    for l_1_h in environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'):
        _loop_vars = {}
        pass
        yield '\n// '
        yield str(environment.getattr(l_1_h, 'title'))
        yield '\nclass '
        yield str(environment.getattr(l_1_h, 'cls'))
        yield ' {\npublic:\n    virtual ~'
        yield str(environment.getattr(l_1_h, 'cls'))
        yield '() = default;\n'
        for l_2_m in environment.getattr(l_1_h, 'methods'):
            _loop_vars = {}
            pass
            yield '\n'
            for l_3_d in environment.getattr(l_2_m, 'doc'):
                _loop_vars = {}
                pass
                yield '    // '
                yield str(l_3_d)
                yield '\n'
            l_3_d = missing
            for l_3_a in environment.getattr(l_2_m, 'params'):
                _loop_vars = {}
                pass
                yield '    //   '
                yield str(environment.getattr(l_3_a, 'doc'))
                yield '\n'
            l_3_a = missing
            yield '    virtual ::rapid_runtime::Result '
            yield str(environment.getattr(l_2_m, 'name'))
            yield '(::rapid_runtime::CommandContext& ctx'
            for l_3_a in environment.getattr(l_2_m, 'params'):
                _loop_vars = {}
                pass
                yield ', '
                yield str(environment.getattr(l_3_a, 'ctype'))
                yield ' '
                yield str(environment.getattr(l_3_a, 'name'))
            l_3_a = missing
            yield ') = 0;\n'
        l_2_m = missing
        yield '};\n'
    l_1_h = missing
    yield '\n// What the bridge runs: one handler per subsystem type (one left empty answers its\n// commands EXEC_FAILED "not implemented"), and hooks called when the bridge has started\n// (publish telemetry of your own: rapid_runtime::dds::Telemetry of\n// <rapid_runtime/dds/telemetry.hpp>) and before it stops.\nstruct HandlerSet {\n'
    for l_1_h in environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'):
        _loop_vars = {}
        pass
        yield '    ::std::unique_ptr<'
        yield str(environment.getattr(l_1_h, 'cls'))
        yield '> '
        yield str(environment.getattr(l_1_h, 'member'))
        yield ';\n'
    l_1_h = missing
    yield '    ::std::function<void(::rapid_runtime::dds::Bridge&)> '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_start'))
    yield ';\n    ::std::function<void()> '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_stop'))
    yield ";\n};\n\n// Yours, in handlers.cpp.\nHandlerSet make_handlers();\n\n// The glue (dispatch.cpp): each command's arguments unpacked into its typed method.\nclass Dispatch final : public ::rapid_runtime::dds::BridgeHandlers {\npublic:\n    explicit Dispatch(HandlerSet set) : set_(::std::move(set)) {}\n    ::rapid_runtime::Result execute(::rapid_runtime::CommandContext& ctx) override;\n    void on_start(::rapid_runtime::dds::Bridge& bridge) override;\n    void on_stop() override;\n\nprivate:\n    HandlerSet set_;\n};\n\n}  // namespace "
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield '\n\n#endif  // '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'guard'))
    yield '_BRIDGE_HANDLERS_HPP\n'

blocks = {}
debug_info = '1=20&2=22&13=24&14=26&27=28&33=30&35=34&36=36&38=38&39=40&41=44&42=48&44=51&45=55&47=59&57=74&58=78&60=84&61=86&79=88&81=90'
