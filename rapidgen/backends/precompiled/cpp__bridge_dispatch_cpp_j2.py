# mypy: ignore-errors
# Template templates/cpp/bridge/dispatch.cpp.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "1a100328a0c0c2a06dcf5c8a2b6e4efeb6b34a18f9370a6e2b9b27209f9d3ca6"
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
    yield ': a command\'s type\n// and name pick the method, its arguments (validated against the tables before) become\n// the method\'s typed parameters.\n#include "handlers.hpp"\n\nnamespace '
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
    yield '    return ::rapid_runtime::Result::failed("not implemented");\n}\n\nvoid Dispatch::on_start(::rapid_runtime::dds::Bridge& bridge) {\n    if (set_.'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_start'))
    yield ') set_.'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_start'))
    yield '(bridge);\n}\n\nvoid Dispatch::on_stop() {\n    if (set_.'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_stop'))
    yield ') set_.'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'on_stop'))
    yield '();\n}\n\n}  // namespace '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'ns'))
    yield '\n'

blocks = {}
debug_info = '1=20&2=22&7=24&10=26&13=30&14=34&15=36&16=39&17=43&18=45&29=67&33=71&36=75'
