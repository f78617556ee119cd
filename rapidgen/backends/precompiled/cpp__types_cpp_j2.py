# mypy: ignore-errors
# Template templates/cpp/types.cpp.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "2e93ca9cd63ceeab25a29dd84e78f4f027f18860a9dcb3509cb68e2fc89ec79b"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'types.cpp.j2'

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
        t_2 = environment.filters['cpp_str']
    except KeyError:
        @internalcode
        def t_2(*unused):
            raise TemplateRuntimeError("No filter named 'cpp_str' found.")
    pass
    yield '// '
    yield str(t_1(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'header')))
    yield '\n// XCDR1 encode/decode of every type in types.hpp: straight-line, bounds checked.\n#include "'
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield '/types.hpp"\n\nnamespace {\n'
    for l_1_e in environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'enums'):
        _loop_vars = {}
        pass
        yield '\n// '
        yield str(t_1(environment.getattr(l_1_e, 'qualified')))
        yield ': only declared values decode.\ntemplate <class R>\n'
        yield str(environment.getattr(l_1_e, 'qualified'))
        yield ' '
        yield str(environment.getattr(l_1_e, 'helper'))
        yield '('
        yield str(environment.getattr(l_1_e, 'type'))
        yield ' x, const R& r) {\n    switch (x) {\n'
        for (l_2_n, l_2_v) in environment.getattr(l_1_e, 'enumerators'):
            _loop_vars = {}
            pass
            yield '    case '
            yield str(l_2_v)
            yield ':\n'
        l_2_n = l_2_v = missing
        yield '        return static_cast<'
        yield str(environment.getattr(l_1_e, 'qualified'))
        yield '>(x);\n    default:\n        r.fail(std::to_string(x) + " is not a value of enum " + '
        yield str(t_2(environment.getattr(l_1_e, 'scoped')))
        yield ');\n    }\n}\n'
    l_1_e = missing
    yield '\n}  // namespace\n'
    l_1_loop = missing
    for l_1_b, l_1_loop in LoopContext(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'blocks'), undefined):
        _loop_vars = {}
        pass
        def t_3(fiter):
            for l_2_d in fiter:
                if (environment.getattr(l_2_d, 'kind') in ('struct', 'union')):
                    yield l_2_d
        l_2_loop = missing
        for l_2_d, l_2_loop in LoopContext(t_3(environment.getattr(l_1_b, 'decls')), undefined):
            _loop_vars = {}
            pass
            if (environment.getattr(l_2_d, 'kind') == 'struct'):
                pass
                yield '\nbool '
                yield str((environment.getattr(l_1_b, 'namespace') and ('::' + environment.getattr(l_1_b, 'namespace'))))
                yield '::operator==(const '
                yield str(environment.getattr(l_2_d, 'qualified'))
                yield '& a, const '
                yield str(environment.getattr(l_2_d, 'qualified'))
                yield '& b) {\n'
                if environment.getattr(l_2_d, 'members'):
                    pass
                    yield '    return '
                    l_3_loop = missing
                    for l_3_m, l_3_loop in LoopContext(environment.getattr(l_2_d, 'members'), undefined):
                        _loop_vars = {}
                        pass
                        yield str((' && ' if (not environment.getattr(l_3_loop, 'first')) else cond_expr_undefined("the inline if-expression on line 29 in 'types.cpp.j2' evaluated to false and no else section was defined.")))
                        yield 'a.'
                        yield str(environment.getattr(l_3_m, 'name'))
                        yield ' == b.'
                        yield str(environment.getattr(l_3_m, 'name'))
                    l_3_loop = l_3_m = missing
                    yield ';\n'
                else:
                    pass
                    yield '    (void)a;\n    (void)b;\n    return true;\n'
                yield '}\n\ntemplate <class W>\nvoid '
                yield str((environment.getattr(l_1_b, 'namespace') and ('::' + environment.getattr(l_1_b, 'namespace'))))
                yield '::encode(W& w, const '
                yield str(environment.getattr(l_2_d, 'qualified'))
                yield '& v) {\n'
                t_4 = 1
                for l_3_s in environment.getattr(l_2_d, 'encode'):
                    _loop_vars = {}
                    pass
                    yield '    '
                    yield str(l_3_s)
                    yield '\n'
                    t_4 = 0
                l_3_s = missing
                if t_4:
                    pass
                    yield '    (void)w;\n    (void)v;\n'
                yield '}\n\ntemplate <class R>\nvoid '
                yield str((environment.getattr(l_1_b, 'namespace') and ('::' + environment.getattr(l_1_b, 'namespace'))))
                yield '::decode(R& r, '
                yield str(environment.getattr(l_2_d, 'qualified'))
                yield '& v) {\n'
                if environment.getattr(l_2_d, 'decode'):
                    pass
                    yield '    typename R::Level level(r);\n'
                t_5 = 1
                for l_3_s in environment.getattr(l_2_d, 'decode'):
                    _loop_vars = {}
                    pass
                    yield '    '
                    yield str(l_3_s)
                    yield '\n'
                    t_5 = 0
                l_3_s = missing
                if t_5:
                    pass
                    yield '    (void)r;\n    (void)v;\n'
                yield '}\n'
                if environment.getattr(l_2_d, 'keyed'):
                    pass
                    yield '\ntemplate <class W>\nvoid '
                    yield str((environment.getattr(l_1_b, 'namespace') and ('::' + environment.getattr(l_1_b, 'namespace'))))
                    yield '::encode_key(W& w, const '
                    yield str(environment.getattr(l_2_d, 'qualified'))
                    yield '& v) {\n'
                    for l_3_s in environment.getattr(l_2_d, 'key'):
                        _loop_vars = {}
                        pass
                        yield '    '
                        yield str(l_3_s)
                        yield '\n'
                    l_3_s = missing
                    yield '}\n'
            else:
                pass
                yield '\ntemplate <class W>\nvoid '
                yield str((environment.getattr(l_1_b, 'namespace') and ('::' + environment.getattr(l_1_b, 'namespace'))))
                yield '::encode(W& w, const '
                yield str(environment.getattr(l_2_d, 'qualified'))
                yield '& v) {\n'
                for l_3_s in environment.getattr(l_2_d, 'encode'):
                    _loop_vars = {}
                    pass
                    yield '    '
                    yield str(l_3_s)
                    yield '\n'
                l_3_s = missing
                yield '    switch (v.m_v.index()) {\n'
                for l_3_c in environment.getattr(l_2_d, 'cases'):
                    _loop_vars = {}
                    pass
                    yield '    case '
                    yield str(environment.getattr(l_3_c, 'index'))
                    yield ': {\n        const auto& x = *std::get_if<'
                    yield str(environment.getattr(l_3_c, 'index'))
                    yield '>(&v.m_v);\n'
                    for l_4_s in environment.getattr(l_3_c, 'encode'):
                        _loop_vars = {}
                        pass
                        yield '        '
                        yield str(l_4_s)
                        yield '\n'
                    l_4_s = missing
                    yield '        break;\n    }\n'
                l_3_c = missing
                yield '    default:\n        break;\n    }\n}\n\ntemplate <class R>\nvoid '
                yield str((environment.getattr(l_1_b, 'namespace') and ('::' + environment.getattr(l_1_b, 'namespace'))))
                yield '::decode(R& r, '
                yield str(environment.getattr(l_2_d, 'qualified'))
                yield '& v) {\n    typename R::Level level(r);\n    '
                yield str(environment.getattr(l_2_d, 'type'))
                yield ' d{};\n'
                for l_3_s in environment.getattr(l_2_d, 'decode'):
                    _loop_vars = {}
                    pass
                    yield '    '
                    yield str(l_3_s)
                    yield '\n'
                l_3_s = missing
                yield '    v.m_d = d;\n    switch ('
                yield str(environment.getattr(l_2_d, 'qualified'))
                yield '::case_of(d)) {\n'
                for l_3_c in environment.getattr(l_2_d, 'cases'):
                    _loop_vars = {}
                    pass
                    yield '    case '
                    yield str(environment.getattr(l_3_c, 'index'))
                    yield ': {\n        auto& x = v.m_v.emplace<'
                    yield str(environment.getattr(l_3_c, 'index'))
                    yield '>('
                    yield str(environment.getattr(l_3_c, 'type'))
                    yield str(environment.getattr(l_3_c, 'init'))
                    yield ');\n'
                    for l_4_s in environment.getattr(l_3_c, 'decode'):
                        _loop_vars = {}
                        pass
                        yield '        '
                        yield str(l_4_s)
                        yield '\n'
                    l_4_s = missing
                    yield '        break;\n    }\n'
                l_3_c = missing
                yield '    default:\n        v.m_v.emplace<0>();\n        break;\n    }\n}\n'
        l_2_loop = l_2_d = missing
    l_1_loop = l_1_b = missing
    yield '\n// The instantiations the package provides: both byte orders, and the counter.\n'
    for l_1_b in environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'blocks'):
        _loop_vars = {}
        pass
        def t_6(fiter):
            for l_2_d in fiter:
                if (environment.getattr(l_2_d, 'kind') in ('struct', 'union')):
                    yield l_2_d
        for l_2_d in t_6(environment.getattr(l_1_b, 'decls')):
            l_2_ns = missing
            _loop_vars = {}
            pass
            l_2_ns = (environment.getattr(l_1_b, 'namespace') and ('::' + environment.getattr(l_1_b, 'namespace')))
            _loop_vars['ns'] = l_2_ns
            for l_3_w in ('Writer', 'SwappedWriter', 'Counter'):
                _loop_vars = {}
                pass
                yield 'template void '
                yield str((undefined(name='ns') if l_2_ns is missing else l_2_ns))
                yield '::encode(::rapidgen::cdr::'
                yield str(l_3_w)
                yield '&, const '
                yield str(environment.getattr(l_2_d, 'qualified'))
                yield '&);\n'
                if environment.getattr(l_2_d, 'keyed'):
                    pass
                    yield 'template void '
                    yield str((undefined(name='ns') if l_2_ns is missing else l_2_ns))
                    yield '::encode_key(::rapidgen::cdr::'
                    yield str(l_3_w)
                    yield '&, const '
                    yield str(environment.getattr(l_2_d, 'qualified'))
                    yield '&);\n'
            l_3_w = missing
            yield 'template void '
            yield str((undefined(name='ns') if l_2_ns is missing else l_2_ns))
            yield '::decode(::rapidgen::cdr::Reader&, '
            yield str(environment.getattr(l_2_d, 'qualified'))
            yield '&);\ntemplate void '
            yield str((undefined(name='ns') if l_2_ns is missing else l_2_ns))
            yield '::decode(::rapidgen::cdr::SwappedReader&, '
            yield str(environment.getattr(l_2_d, 'qualified'))
            yield '&);\n'
        l_2_d = l_2_ns = missing
    l_1_b = missing

blocks = {}
debug_info = '1=25&3=27&6=29&8=33&10=35&12=41&13=45&15=49&17=51&23=56&24=59&25=67&27=70&28=76&29=80&38=94&39=99&40=103&48=111&49=115&52=119&53=123&59=131&62=134&63=138&64=142&71=149&72=153&73=157&76=161&77=165&78=167&79=169&80=173&91=179&93=183&94=185&95=189&98=193&99=195&100=199&101=201&102=206&103=210&118=219&119=222&120=230&121=232&122=236&123=242&124=245&127=253&128=257'
