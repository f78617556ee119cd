# mypy: ignore-errors
# Template templates/cpp/topics.hpp.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "dac92516aecd681f63956e65dd1f17a94535a7321961af0fa2e30444cf2c0e84"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'topics.hpp.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_p = resolve('p')
    try:
        t_1 = environment.filters['cpp_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'cpp_comment' found.")
    pass
    yield '// '
    yield str(t_1(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'header')))
    yield '\n// A Fast DDS 2.9 TopicDataType per struct: `rapid::CommandPubSubType` registers the type\n// name `rapid::Command`, as RAPID peers and the generated QoS expect.\n#ifndef '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'guard'))
    yield '_TOPICS_HPP\n#define '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'guard'))
    yield '_TOPICS_HPP\n\n#include "dds.hpp"\n#include "types.hpp"\n\nnamespace rapidgen {\nnamespace dds {\n'
    for l_1_t in environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'topics'):
        _loop_vars = {}
        pass
        yield '\ntemplate <>\nstruct Traits<'
        yield str(environment.getattr(l_1_t, 'qualified'))
        yield '> {\n    static constexpr const char* name = '
        yield str(environment.getattr(l_1_t, 'type_name'))
        yield ';\n    static constexpr bool keyed = '
        yield str(('true' if environment.getattr(l_1_t, 'keyed') else 'false'))
        yield ';\n    static constexpr std::size_t key_max = '
        yield str(environment.getattr(l_1_t, 'key_max'))
        yield 'u;\n    static constexpr std::uint32_t initial_size = '
        yield str(environment.getattr(l_1_t, 'initial'))
        yield 'u;\n'
        if environment.getattr(l_1_t, 'keyed'):
            pass
            yield '    template <class W>\n    static void key(W& w, const '
            yield str(environment.getattr(l_1_t, 'qualified'))
            yield '& v) { encode_key(w, v); }\n'
        yield '};\n'
    l_1_t = missing
    yield '\n}  // namespace dds\n}  // namespace rapidgen\n'
    for l_1_t in environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'topics'):
        _loop_vars = {}
        pass
        yield '\n'
        if environment.getattr(l_1_t, 'namespace'):
            pass
            yield 'namespace '
            yield str(environment.getattr(l_1_t, 'namespace'))
            yield ' { '
        yield 'using '
        yield str(environment.getattr(l_1_t, 'alias'))
        yield ' = ::rapidgen::dds::TopicType<'
        yield str(environment.getattr(l_1_t, 'qualified'))
        yield '>;'
        if environment.getattr(l_1_t, 'namespace'):
            pass
            yield ' }'
        yield '\n'
    l_1_t = missing
    yield '\n#endif  // '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'guard'))
    yield '_TOPICS_HPP\n'

blocks = {}
debug_info = '1=19&4=21&5=23&12=25&15=29&16=31&17=33&18=35&19=37&20=39&22=42&29=47&31=51&35=67'
