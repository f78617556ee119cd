# mypy: ignore-errors
# Template templates/cpp/asset.hpp.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "215e1d43132980b73b97a8703f6b24f8e43f90298fec4ee15cde79a4ff899b43"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'asset.hpp.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_p = resolve('p')
    l_0_a = resolve('a')
    try:
        t_1 = environment.filters['cpp_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'cpp_comment' found.")
    try:
        t_2 = environment.filters['length']
    except KeyError:
        @internalcode
        def t_2(*unused):
            raise TemplateRuntimeError("No filter named 'length' found.")
    pass
    yield '// '
    yield str(t_1(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'header')))
    yield '\n// The asset as constants: what it publishes and its computed configs (the command\n// dictionary is the CommandConfig), so a C++ robot needs no rapidgen at run time.\n#ifndef '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'guard'))
    yield '_ASSET_HPP\n#define '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'guard'))
    yield '_ASSET_HPP\n\n#include <array>\n#include <string_view>\n\n#include "types.hpp"\n\nnamespace '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ' {\n\ninline constexpr std::string_view ASSET_NAME = '
    yield str(environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'name'))
    yield ';\ninline constexpr std::string_view ASSET_KIND = '
    yield str(environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'kind'))
    yield ';\ninline constexpr int DOMAIN_ID = '
    yield str(environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'domain'))
    yield ';\ninline constexpr std::string_view PARTITION = '
    yield str(environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'partition'))
    yield ';\n\n// Every topic the asset publishes; `qos` is the profile name in qos/fastdds/rapid_qos_profiles.xml.\nstruct Publication {\n    std::string_view role;  // config, state, sample or ack\n    std::string_view type;  // the DDS type name\n    std::string_view topic;\n    std::string_view qos;\n};\n\ninline constexpr std::array<Publication, '
    yield str(t_2(environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'publications')))
    yield '> PUBLICATIONS = {{\n'
    for l_1_q in environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'publications'):
        _loop_vars = {}
        pass
        yield '    {'
        yield str(environment.getattr(l_1_q, 'role'))
        yield ', '
        yield str(environment.getattr(l_1_q, 'type'))
        yield ', '
        yield str(environment.getattr(l_1_q, 'topic'))
        yield ', '
        yield str(environment.getattr(l_1_q, 'qos'))
        yield '},\n'
    l_1_q = missing
    yield '}};\n'
    for l_1_c in environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'configs'):
        _loop_vars = {}
        pass
        yield '\n// The config published on '
        yield str(environment.getattr(l_1_c, 'topic'))
        yield '.\ninline '
        yield str(environment.getattr(l_1_c, 'type'))
        yield ' '
        yield str(environment.getattr(l_1_c, 'function'))
        yield '() {\n    return '
        yield str(environment.getattr(l_1_c, 'expr'))
        yield ';\n}\n'
    l_1_c = missing
    yield '\n}  // namespace '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield '\n\n#endif  // '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'guard'))
    yield '_ASSET_HPP\n'

blocks = {}
debug_info = '1=26&4=28&5=30&12=32&14=34&15=36&16=38&17=40&27=42&28=44&29=48&32=58&34=62&35=64&36=68&40=72&42=74'
