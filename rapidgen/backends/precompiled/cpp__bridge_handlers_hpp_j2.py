# mypy: ignore-errors
# Template templates/cpp/bridge/handlers.hpp.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "5d8800b297840b8f1236b5001317cba935b2912cdbf88aaf3ed76bc280788673"
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
    l_0_st = resolve('st')
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
    yield '_BRIDGE_HANDLERS_HPP\n\n#include <array>\n#include <cstdint>\n#include <functional>\n#include <memory>\n#include <string>\n#include <string_view>\n\n'
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'):
        pass
        yield '#include <map>\n\n'
    yield '#include <rapid_runtime/dds/bridge_handlers.hpp>\n#include <rapid_runtime/handlers.hpp>\n#include <rapid_runtime/tables.hpp>\n'
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'):
        pass
        yield '#include <rapid_runtime/stream.hpp>\n#include <rapid_runtime/value.hpp>\n#include <'
        yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'package'))
        yield '/types.hpp>\n\nnamespace rapid_runtime {\nclass Simulator;\nnamespace dds { class Bridge; class StreamSet; }\n}  // namespace rapid_runtime\n'
    yield '\nnamespace '
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
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'):
        pass
        l_0_st = environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams')
        context.vars['st'] = l_0_st
        context.exported_vars.add('st')
        yield "\n// The asset's setpoint streams (docs/realtime.md), read outside the command queue with\n// DEADLINE and LIVELINESS QoS (profiles RapidStream_<name>). Each input stream's method is\n// called for every sample on Fast DDS's receive thread: keep it short, lock-free and\n// allocation-free (copy the setpoint where the control loop reads it). The runtime watches\n// the deadline: on a loss it runs the declared action (stop: "
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'state_hook'))
        yield '() is your\n// cue to bring the driven joints to rest, and Mobility/stopAllMotion goes through the\n// command manager when the asset has Mobility; hold: keep the last setpoint), sends a\n// TextMessage and reports the state in AgentState. Under --simulate the simulated robot\n// takes the samples instead (JointSample and PositionSample setpoints move it) and writes\n// the output streams.\nclass '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'cls'))
        yield ' {\npublic:\n    virtual ~'
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'cls'))
        yield '() = default;\n'
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'inputs'):
            _loop_vars = {}
            pass
            yield '\n'
            for l_2_d in environment.getattr(l_1_s, 'doc'):
                _loop_vars = {}
                pass
                yield '    // '
                yield str(l_2_d)
                yield '\n'
            l_2_d = missing
            yield '    virtual void '
            yield str(environment.getattr(l_1_s, 'method'))
            yield '(const '
            yield str(environment.getattr(l_1_s, 'type'))
            yield '& sample) { (void)sample; }\n'
        l_1_s = missing
        yield "\n    // A stream with on_loss stop or hold changed state: lost (the declared action is being\n    // taken) or active (first sample, recovered). Runs on the runtime's reporting thread.\n    // Not called for on_loss none: the runtime only reports those.\n    virtual void "
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'state_hook'))
        yield '(const ::rapid_runtime::StreamSpec& stream, ::rapid_runtime::StreamState state) {\n        (void)stream;\n        (void)state;\n    }\n};\n'
        l_1_loop = missing
        for l_1_s, l_1_loop in LoopContext(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'outputs'), undefined):
            _loop_vars = {}
            pass
            yield '\n'
            l_2_loop = missing
            for l_2_d, l_2_loop in LoopContext(environment.getattr(l_1_s, 'doc'), undefined):
                _loop_vars = {}
                pass
                yield '// '
                if environment.getattr(l_2_loop, 'first'):
                    pass
                    yield 'Output stream '
                yield str(l_2_d)
                yield '\n'
            l_2_loop = l_2_d = missing
            yield '// Fill '
            yield str(environment.getattr(l_1_s, 'sample_fn'))
            yield '() in place (one sample kept for the whole run: nothing allocates once\n// its sequences have their size), then '
            yield str(environment.getattr(l_1_s, 'send_fn'))
            yield '() stamps and writes it (false before the\n// bridge started or after it stopped, or when Fast DDS refused it).\n'
            yield str(environment.getattr(l_1_s, 'type'))
            yield '& '
            yield str(environment.getattr(l_1_s, 'sample_fn'))
            yield '();\nbool '
            yield str(environment.getattr(l_1_s, 'send_fn'))
            yield '();\n'
        l_1_loop = l_1_s = missing
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
    yield ';\n'
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'):
        pass
        yield "    // The input streams' callbacks (none: samples are counted and watched only).\n    ::std::unique_ptr<"
        yield str(environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'cls'))
        yield '> '
        yield str(environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'member'))
        yield ";\n    // Your agent values: the runtime publishes AgentState with the streams' state keys and\n    // these (unset: the declared defaults) at the agent telemetry's rate.\n    ::std::function<::std::map<::std::string, ::rapid_runtime::Value>()> "
        yield str(environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'values'))
        yield ';\n'
    yield '};\n\n// Yours, in handlers.cpp.\nHandlerSet make_handlers();\n'
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'):
        pass
        yield '\n// The glue (dispatch.cpp): the streams on the simulated robot (--simulate).\n::std::shared_ptr<void> '
        yield str(environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'simulate'))
        yield '(::rapid_runtime::dds::Bridge& bridge, ::rapid_runtime::Simulator& sim);\n'
    yield "\n// The glue (dispatch.cpp): each command's arguments unpacked into its typed method.\nclass Dispatch final : public ::rapid_runtime::dds::BridgeHandlers {\npublic:\n    explicit Dispatch(HandlerSet set) : set_(::std::move(set)) {}\n"
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'):
        pass
        yield '    ~Dispatch() override;\n'
    yield '    ::rapid_runtime::Result execute(::rapid_runtime::CommandContext& ctx) override;\n    void on_start(::rapid_runtime::dds::Bridge& bridge) override;\n    void on_stop() override;\n\nprivate:\n    HandlerSet set_;\n'
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'):
        pass
        yield '    ::std::shared_ptr<::rapid_runtime::dds::StreamSet> streams_;  // shared: its type is incomplete here\n'
    yield '};\n\n}  // namespace '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield '\n\n#endif  // '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'guard'))
    yield '_BRIDGE_HANDLERS_HPP\n'

blocks = {}
debug_info = '1=21&2=23&13=25&14=27&23=29&30=33&33=36&41=39&47=41&49=45&50=47&52=49&53=51&55=55&56=59&58=62&59=66&61=70&65=84&66=86&72=90&78=92&80=94&81=96&83=100&84=104&86=108&92=114&97=117&99=122&100=126&102=133&103=135&105=137&106=141&115=145&116=149&118=155&119=157&120=159&122=162&125=166&131=169&134=172&141=175&150=179&155=183&157=185'
