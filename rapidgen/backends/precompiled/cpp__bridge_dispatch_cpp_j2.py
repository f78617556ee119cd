# mypy: ignore-errors
# Template templates/cpp/bridge/dispatch.cpp.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "5a2a4782cb5e9e4555461fac2952cf74db700e3e4465e5623a8c13ca1cb749ac"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge/dispatch.cpp.j2'

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
    yield '\n// The glue between the runtime and the handlers of asset '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'asset'))
    yield ': a command\'s type\n// and name pick the method, its arguments (validated against the tables before) become\n// the method\'s typed parameters.\n#include "handlers.hpp"\n'
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'):
        pass
        yield '\n#include <atomic>\n#include <memory>\n#include <vector>\n\n#include <rapid_runtime/dds/stream.hpp>\n'
    yield '\nnamespace '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield ' {\n\n::rapid_runtime::Result Dispatch::execute(::rapid_runtime::CommandContext& ctx) {\n'
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'):
        pass
        yield '    const ::std::string& type = ctx.type();\n    const ::std::string& name = ctx.command();\n'
        l_1_loop = missing
        for l_1_h, l_1_loop in LoopContext(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'), undefined):
            _loop_vars = {}
            pass
            yield '    if (type == '
            yield str(environment.getattr(l_1_h, 'type'))
            yield ') {\n        if (!set_.'
            yield str(environment.getattr(l_1_h, 'member'))
            yield ') return ::rapid_runtime::Result::failed("not implemented");\n'
            l_2_loop = missing
            for l_2_m, l_2_loop in LoopContext(environment.getattr(l_1_h, 'methods'), undefined):
                _loop_vars = {}
                pass
                yield '        if (name == '
                yield str(environment.getattr(l_2_m, 'command'))
                yield ')\n            return set_.'
                yield str(environment.getattr(l_1_h, 'member'))
                yield '->'
                yield str(environment.getattr(l_2_m, 'name'))
                yield '(ctx'
                l_3_loop = missing
                for l_3_a, l_3_loop in LoopContext(environment.getattr(l_2_m, 'params'), undefined):
                    _loop_vars = {}
                    pass
                    yield ', ctx.arg<'
                    yield str(environment.getattr(l_3_a, 'get'))
                    yield '>('
                    yield str(environment.getattr(l_3_loop, 'index0'))
                    yield ')'
                l_3_loop = l_3_a = missing
                yield ');\n'
            l_2_loop = l_2_m = missing
            yield '    }\n'
        l_1_loop = l_1_h = missing
    else:
        pass
        yield '    (void)ctx;\n'
    yield '    return ::rapid_runtime::Result::failed("not implemented");\n}\n\n'
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'):
        pass
        l_0_st = environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams')
        context.vars['st'] = l_0_st
        context.exported_vars.add('st')
        yield "namespace {\n\n// The running bridge's streams, for the output streams' free functions.\n::std::atomic<::rapid_runtime::dds::StreamSet*> running{nullptr};\n\n::std::vector<::rapid_runtime::StreamSpec> stream_specs() {\n    return {\n"
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'streams'):
            _loop_vars = {}
            pass
            yield '        '
            yield str(environment.getattr(l_1_s, 'spec'))
            yield ',\n'
        l_1_s = missing
        yield '    };\n}\n\n}  // namespace\n\nDispatch::~Dispatch() = default;\n\nvoid Dispatch::on_start(::rapid_runtime::dds::Bridge& bridge) {\n    ::rapid_runtime::dds::StreamHooks hooks;\n    hooks.on_state = [this](const ::rapid_runtime::StreamSpec& s, ::rapid_runtime::StreamState state) {\n        if (set_.'
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'member'))
        yield ') set_.'
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'member'))
        yield '->'
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'state_hook'))
        yield '(s, state);\n    };\n    if (set_.'
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'values'))
        yield ') hooks.agent_values = set_.'
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'values'))
        yield ';\n    streams_ = ::std::make_shared<::rapid_runtime::dds::StreamSet>(bridge, stream_specs(), ::std::move(hooks));\n'
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'inputs'):
            _loop_vars = {}
            pass
            yield '    streams_->read<'
            yield str(environment.getattr(l_1_s, 'type'))
            yield '>('
            yield str(environment.getattr(l_1_s, 'index'))
            yield 'u, [this](const '
            yield str(environment.getattr(l_1_s, 'type'))
            yield '& sample) {\n        if (set_.'
            yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'member'))
            yield ') set_.'
            yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'member'))
            yield '->'
            yield str(environment.getattr(l_1_s, 'method'))
            yield '(sample);\n    });\n'
        l_1_s = missing
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'outputs'):
            _loop_vars = {}
            pass
            yield '    streams_->writer<'
            yield str(environment.getattr(l_1_s, 'type'))
            yield '>('
            yield str(environment.getattr(l_1_s, 'index'))
            yield 'u);\n'
        l_1_s = missing
        yield '    streams_->start();\n    running = streams_.get();\n    if (set_.'
        yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_start'))
        yield ') set_.'
        yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_start'))
        yield '(bridge);\n}\n\nvoid Dispatch::on_stop() {\n    if (set_.'
        yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_stop'))
        yield ') set_.'
        yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_stop'))
        yield '();\n    running = nullptr;\n    if (streams_) streams_->stop();\n}\n\n::std::shared_ptr<void> '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'simulate'))
        yield '(::rapid_runtime::dds::Bridge& bridge, ::rapid_runtime::Simulator& sim) {\n    auto set = ::std::make_shared<::rapid_runtime::dds::SimulatedStreams>(bridge, sim, stream_specs());\n'
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'inputs'):
            _loop_vars = {}
            pass
            yield '    set->read<'
            yield str(environment.getattr(l_1_s, 'type'))
            yield '>('
            yield str(environment.getattr(l_1_s, 'index'))
            yield 'u);\n'
        l_1_s = missing
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'outputs'):
            _loop_vars = {}
            pass
            yield '    set->write<'
            yield str(environment.getattr(l_1_s, 'type'))
            yield '>('
            yield str(environment.getattr(l_1_s, 'index'))
            yield 'u);\n'
        l_1_s = missing
        yield '    set->start();\n    return set;\n}\n'
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'outputs'):
            _loop_vars = {}
            pass
            yield '\n'
            yield str(environment.getattr(l_1_s, 'type'))
            yield '& '
            yield str(environment.getattr(l_1_s, 'sample_fn'))
            yield '() {\n    static '
            yield str(environment.getattr(l_1_s, 'type'))
            yield ' unused{};  // before start and after stop: written nowhere\n    auto* set = running.load();\n    return set != nullptr ? set->writer<'
            yield str(environment.getattr(l_1_s, 'type'))
            yield '>('
            yield str(environment.getattr(l_1_s, 'index'))
            yield 'u).sample() : unused;\n}\n\nbool '
            yield str(environment.getattr(l_1_s, 'send_fn'))
            yield '() {\n    auto* set = running.load();\n    return set != nullptr && set->writer<'
            yield str(environment.getattr(l_1_s, 'type'))
            yield '>('
            yield str(environment.getattr(l_1_s, 'index'))
            yield 'u).write();\n}\n'
        l_1_s = missing
    else:
        pass
        yield 'void Dispatch::on_start(::rapid_runtime::dds::Bridge& bridge) {\n    if (set_.'
        yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_start'))
        yield ') set_.'
        yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_start'))
        yield '(bridge);\n}\n\nvoid Dispatch::on_stop() {\n    if (set_.'
        yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_stop'))
        yield ') set_.'
        yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_stop'))
        yield '();\n}\n'
    yield '\n}  // namespace '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield '\n'

blocks = {}
debug_info = '1=21&2=23&6=25&15=29&18=31&21=35&22=39&23=41&24=44&25=48&26=50&36=72&37=74&45=78&46=82&58=86&60=92&62=96&63=100&64=106&67=113&68=117&72=123&76=127&81=131&83=133&84=137&86=142&87=146&92=152&94=156&95=160&97=162&100=166&102=168&107=176&111=180&115=185'
