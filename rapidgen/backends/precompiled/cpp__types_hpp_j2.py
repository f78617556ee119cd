# mypy: ignore-errors
# Template templates/cpp/types.hpp.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "80236b6f4babdcaeb7e06ae9abcc3c11d7a0e722fde7a999d7face60c33f5c42"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'types.hpp.j2'

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
    try:
        t_2 = environment.filters['list']
    except KeyError:
        @internalcode
        def t_2(*unused):
            raise TemplateRuntimeError("No filter named 'list' found.")
    try:
        t_3 = environment.filters['selectattr']
    except KeyError:
        @internalcode
        def t_3(*unused):
            raise TemplateRuntimeError("No filter named 'selectattr' found.")
    pass
    yield '// '
    yield str(t_1(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'header')))
    yield '\n// C++17 types of '
    yield str(t_1(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'source')))
    yield ': one namespace per IDL module, value semantics,\n// XCDR1 encode/decode (types.cpp: instantiated for the writers, the counter and the\n// readers of cdr.hpp). docs/cpp-backend.md has the mapping.\n#ifndef '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'guard'))
    yield '_TYPES_HPP\n#define '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'guard'))
    yield '_TYPES_HPP\n\n#include <array>\n#include <cstdint>\n#include <limits>\n#include <stdexcept>\n#include <string>\n#include <string_view>\n#include <utility>\n#include <variant>\n#include <vector>\n\n#include "cdr.hpp"\n'
    for l_1_b in environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'blocks'):
        _loop_vars = {}
        pass
        yield '\n'
        if environment.getattr(l_1_b, 'namespace'):
            pass
            yield 'namespace '
            yield str(environment.getattr(l_1_b, 'namespace'))
            yield ' {\n'
        for l_2_d in environment.getattr(l_1_b, 'decls'):
            l_2_dflt = resolve('dflt')
            _loop_vars = {}
            pass
            yield '\n// '
            yield str(t_1(environment.getattr(l_2_d, 'doc')))
            yield '\n'
            if (environment.getattr(l_2_d, 'kind') == 'typedef'):
                pass
                yield 'using '
                yield str(environment.getattr(l_2_d, 'name'))
                yield ' = '
                yield str(environment.getattr(l_2_d, 'type'))
                yield ';\n'
            elif (environment.getattr(l_2_d, 'kind') == 'const'):
                pass
                yield 'inline constexpr '
                yield str(environment.getattr(l_2_d, 'type'))
                yield ' '
                yield str(environment.getattr(l_2_d, 'name'))
                yield ' = '
                yield str(environment.getattr(l_2_d, 'value'))
                yield ';\n'
            elif (environment.getattr(l_2_d, 'kind') == 'enum'):
                pass
                yield 'enum class '
                yield str(environment.getattr(l_2_d, 'name'))
                yield ' : '
                yield str(environment.getattr(l_2_d, 'type'))
                yield ' {\n'
                for (l_3_n, l_3_v) in environment.getattr(l_2_d, 'enumerators'):
                    _loop_vars = {}
                    pass
                    yield '    '
                    yield str(l_3_n)
                    yield ' = '
                    yield str(l_3_v)
                    yield ',\n'
                l_3_n = l_3_v = missing
                yield '};\n'
            elif (environment.getattr(l_2_d, 'kind') == 'struct'):
                pass
                yield 'struct '
                yield str(environment.getattr(l_2_d, 'name'))
                yield ' {\n'
                for l_3_m in environment.getattr(l_2_d, 'members'):
                    _loop_vars = {}
                    pass
                    yield '    '
                    yield str(environment.getattr(l_3_m, 'type'))
                    yield ' '
                    yield str(environment.getattr(l_3_m, 'name'))
                    yield str(environment.getattr(l_3_m, 'init'))
                    yield ';\n'
                l_3_m = missing
                yield '};\nbool operator==(const '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& a, const '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& b);\ninline bool operator!=(const '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& a, const '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& b) { return !(a == b); }\ntemplate <class W>\nvoid encode(W& w, const '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& v);\ntemplate <class R>\nvoid decode(R& r, '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& v);\n'
                if environment.getattr(l_2_d, 'keyed'):
                    pass
                    yield 'template <class W>\nvoid encode_key(W& w, const '
                    yield str(environment.getattr(l_2_d, 'name'))
                    yield '& v);\n'
            elif (environment.getattr(l_2_d, 'kind') == 'union'):
                pass
                yield 'class '
                yield str(environment.getattr(l_2_d, 'name'))
                yield ' {\npublic:\n    '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '() : m_d('
                yield str(environment.getattr(l_2_d, 'default_disc'))
                yield '), m_v(std::in_place_index<'
                yield str(environment.getattr(l_2_d, 'default_index'))
                yield '>'
                def t_4(fiter):
                    for l_3_c in fiter:
                        if (environment.getattr(l_3_c, 'index') == environment.getattr(l_2_d, 'default_index')):
                            yield l_3_c
                for l_3_c in t_4(environment.getattr(l_2_d, 'cases')):
                    _loop_vars = {}
                    pass
                    yield ', '
                    yield str(environment.getattr(l_3_c, 'type'))
                    yield str(environment.getattr(l_3_c, 'init'))
                l_3_c = missing
                yield ') {}\n\n    '
                yield str(environment.getattr(l_2_d, 'type'))
                yield ' _d() const { return m_d; }\n    // Another discriminator value of the same member; anything else is std::invalid_argument.\n    void _d('
                yield str(environment.getattr(l_2_d, 'type'))
                yield ' d) {\n        if (case_of(d) != m_v.index()) throw std::invalid_argument("'
                yield str(environment.getattr(l_2_d, 'name'))
                yield ': discriminator selects another member");\n        m_d = d;\n    }\n'
                for l_3_c in environment.getattr(l_2_d, 'cases'):
                    _loop_vars = {}
                    pass
                    yield '\n    const '
                    yield str(environment.getattr(l_3_c, 'type'))
                    yield '& '
                    yield str(environment.getattr(l_3_c, 'name'))
                    yield '() const { check('
                    yield str(environment.getattr(l_3_c, 'index'))
                    yield '); return std::get<'
                    yield str(environment.getattr(l_3_c, 'index'))
                    yield '>(m_v); }\n    '
                    yield str(environment.getattr(l_3_c, 'type'))
                    yield '& '
                    yield str(environment.getattr(l_3_c, 'name'))
                    yield '() { check('
                    yield str(environment.getattr(l_3_c, 'index'))
                    yield '); return std::get<'
                    yield str(environment.getattr(l_3_c, 'index'))
                    yield '>(m_v); }\n    void '
                    yield str(environment.getattr(l_3_c, 'name'))
                    yield '('
                    yield str(environment.getattr(l_3_c, 'type'))
                    yield ' value) {\n        m_d = '
                    yield str(environment.getattr(l_3_c, 'select'))
                    yield ';\n        m_v.emplace<'
                    yield str(environment.getattr(l_3_c, 'index'))
                    yield '>(std::move(value));\n    }\n'
                l_3_c = missing
                yield '\n    // The member index a discriminator value selects (0: none).\n    static std::size_t case_of('
                yield str(environment.getattr(l_2_d, 'type'))
                yield ' d) {\n'
                def t_5(fiter):
                    for l_3_c in fiter:
                        if environment.getattr(l_3_c, 'cond'):
                            yield l_3_c
                for l_3_c in t_5(environment.getattr(l_2_d, 'cases')):
                    _loop_vars = {}
                    pass
                    yield '        if ('
                    yield str(environment.getattr(l_3_c, 'cond'))
                    yield ') return '
                    yield str(environment.getattr(l_3_c, 'index'))
                    yield ';\n'
                l_3_c = missing
                l_2_dflt = t_2(context.eval_ctx, t_3(context, environment.getattr(l_2_d, 'cases'), 'cond', 'equalto', ''))
                _loop_vars['dflt'] = l_2_dflt
                yield '        (void)d;\n        return '
                yield str((environment.getattr(environment.getitem((undefined(name='dflt') if l_2_dflt is missing else l_2_dflt), 0), 'index') if (undefined(name='dflt') if l_2_dflt is missing else l_2_dflt) else 0))
                yield ';\n    }\n\n    friend bool operator==(const '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& a, const '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& b) { return a.m_d == b.m_d && a.m_v == b.m_v; }\n    friend bool operator!=(const '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& a, const '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& b) { return !(a == b); }\n    template <class W>\n    friend void encode(W& w, const '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& v);\n    template <class R>\n    friend void decode(R& r, '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& v);\n\nprivate:\n    void check(std::size_t index) const {\n        if (m_v.index() != index) throw std::logic_error("'
                yield str(environment.getattr(l_2_d, 'name'))
                yield ': not the selected member");\n    }\n\n    '
                yield str(environment.getattr(l_2_d, 'type'))
                yield ' m_d;\n    std::variant<std::monostate'
                for l_3_c in environment.getattr(l_2_d, 'cases'):
                    _loop_vars = {}
                    pass
                    yield ', '
                    yield str(environment.getattr(l_3_c, 'type'))
                l_3_c = missing
                yield '> m_v;\n};\ntemplate <class W>\nvoid encode(W& w, const '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& v);\ntemplate <class R>\nvoid decode(R& r, '
                yield str(environment.getattr(l_2_d, 'name'))
                yield '& v);\n'
        l_2_d = l_2_dflt = missing
        if environment.getattr(l_1_b, 'namespace'):
            pass
            yield '\n}  // namespace '
            yield str(environment.getattr(l_1_b, 'namespace'))
            yield '\n'
    l_1_b = missing
    yield '\n#endif  // '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'guard'))
    yield '_TYPES_HPP\n'

blocks = {}
debug_info = '1=31&2=33&5=35&6=37&19=39&21=43&22=46&24=48&26=53&27=55&28=58&29=62&30=65&31=71&32=74&33=78&34=82&37=88&38=91&39=93&40=97&43=104&44=108&46=112&48=114&49=116&51=119&53=121&54=124&56=126&58=144&60=146&61=148&64=150&66=154&67=162&68=170&69=174&70=176&75=180&76=182&77=190&79=195&81=198&84=200&85=204&87=208&89=210&93=212&96=214&97=216&100=223&102=225&105=228&107=231&111=235'
