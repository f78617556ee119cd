# mypy: ignore-errors
# Template templates/cpp/bridge/handlers.cpp.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "833a9019bc6efae59c989f28f3047c0553f4135137771f42f02b3b019ac97f6d"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge/handlers.cpp.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_v = resolve('v')
    pass
    yield '// Handlers of asset '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'asset'))
    yield ': written once by rapidgen, yours to edit.\n// Regeneration never touches this file (delete it to get fresh stubs). When the\n// descriptor changes, handlers.hpp changes with it and the compiler says what to update.\n//\n// Every method answers EXEC_FAILED "not implemented" until you write it; see handlers.hpp\n// for the rules (results, progress, cancellation). `'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'package'))
    yield '_bridge --simulate` runs\n// a simulated robot instead of these. To publish telemetry of your own, set\n// HandlerSet::'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_start'))
    yield ' and use rapid_runtime::dds::Telemetry\n// (#include <rapid_runtime/dds/telemetry.hpp>).\n#include "handlers.hpp"\n\nnamespace '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield ' {\n'
    if (environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers') or (environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams') and environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'inputs'))):
        pass
        yield '\nnamespace {\n'
        l_1_loop = missing
        for l_1_h, l_1_loop in LoopContext(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'), undefined):
            _loop_vars = {}
            pass
            yield '\nclass '
            yield str(environment.getattr(l_1_h, 'impl'))
            yield ' final : public '
            yield str(environment.getattr(l_1_h, 'cls'))
            yield ' {\npublic:\n'
            l_2_loop = missing
            for l_2_m, l_2_loop in LoopContext(environment.getattr(l_1_h, 'methods'), undefined):
                _loop_vars = {}
                pass
                if (not environment.getattr(l_2_loop, 'first')):
                    pass
                    yield '\n'
                yield '    // '
                yield str(environment.getitem(environment.getattr(l_2_m, 'doc'), 0))
                yield '\n    ::rapid_runtime::Result '
                yield str(environment.getattr(l_2_m, 'name'))
                yield '([[maybe_unused]] ::rapid_runtime::CommandContext& ctx'
                for l_3_a in environment.getattr(l_2_m, 'params'):
                    _loop_vars = {}
                    pass
                    yield ',\n        [[maybe_unused]] '
                    yield str(environment.getattr(l_3_a, 'ctype'))
                    yield ' '
                    yield str(environment.getattr(l_3_a, 'name'))
                l_3_a = missing
                yield ') override {\n        return ::rapid_runtime::Result::failed("not implemented");\n    }\n'
            l_2_loop = l_2_m = missing
            yield '};\n'
        l_1_loop = l_1_h = missing
        if (environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams') and environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'inputs')):
            pass
            yield '\nclass '
            yield str(environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'impl'))
            yield ' final : public '
            yield str(environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'cls'))
            yield ' {\npublic:\n'
            l_1_loop = missing
            for l_1_s, l_1_loop in LoopContext(environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'inputs'), undefined):
                _loop_vars = {}
                pass
                if (not environment.getattr(l_1_loop, 'first')):
                    pass
                    yield '\n'
                yield '    // '
                yield str(environment.getitem(environment.getattr(l_1_s, 'doc'), 0))
                yield '\n    void '
                yield str(environment.getattr(l_1_s, 'method'))
                yield '([[maybe_unused]] const '
                yield str(environment.getattr(l_1_s, 'type'))
                yield '& sample) override {\n        // the new setpoint: hand it to your control loop (no locks, no allocation here)\n    }\n'
            l_1_loop = l_1_s = missing
            yield '\n    void '
            yield str(environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'state_hook'))
            yield '([[maybe_unused]] const ::rapid_runtime::StreamSpec& stream,\n                  [[maybe_unused]] ::rapid_runtime::StreamState state) override {\n        // lost with on_loss stop: bring the joints the stream drives to rest\n    }\n};\n'
        yield '\n}  // namespace\n'
    yield '\nHandlerSet make_handlers() {\n    HandlerSet set;\n'
    t_1 = 1
    for l_1_h in environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'):
        _loop_vars = {}
        pass
        yield '    set.'
        yield str(environment.getattr(l_1_h, 'member'))
        yield ' = ::std::make_unique<'
        yield str(environment.getattr(l_1_h, 'impl'))
        yield '>();\n'
        t_1 = 0
    l_1_h = missing
    if t_1:
        pass
        yield '    // (the asset takes no commands of its own: no handler to make)\n'
    if (environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams') and environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'inputs')):
        pass
        yield '    set.'
        yield str(environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'member'))
        yield ' = ::std::make_unique<'
        yield str(environment.getattr(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'), 'impl'))
        yield '>();\n'
    yield '    return set;\n}\n\n}  // namespace '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield '\n'

blocks = {}
debug_info = '1=13&6=15&8=17&12=19&13=21&16=25&18=29&20=34&21=37&24=41&25=43&26=49&32=57&34=60&36=65&37=68&40=72&41=74&46=80&58=85&59=89&63=98&64=101&69=106'
