# mypy: ignore-errors
# Template templates/cpp/CMakeLists.txt.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "c23d263d37b61606051cd0c6fb5a9811985e58b54e2b32fdda5ae8a8d488686e"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'CMakeLists.txt.j2'

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
    yield '# '
    yield str(t_1(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'header')))
    yield '\n# C++17 types and Fast DDS 2.9 topic types of '
    yield str(t_1(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'source')))
    yield '.\n# Use: find_package('
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ') then target_link_libraries(app '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield '::'
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield '),\n# after `cmake --install`, or with '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield "_DIR set to this project's build folder.\ncmake_minimum_required(VERSION 3.16)\nproject("
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ' VERSION 1.0.0 LANGUAGES CXX)\n\nfind_package(fastcdr REQUIRED)\nfind_package(fastrtps REQUIRED)\n\nadd_library('
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ' src/types.cpp)\nadd_library('
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield '::'
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ' ALIAS '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ')\ntarget_compile_features('
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ' PUBLIC cxx_std_17)\nset_target_properties('
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ' PROPERTIES CXX_EXTENSIONS OFF POSITION_INDEPENDENT_CODE ON)\ntarget_include_directories('
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ' PUBLIC\n    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>\n    $<INSTALL_INTERFACE:include>)\ntarget_link_libraries('
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ' PUBLIC fastrtps fastcdr)\n\ninclude(GNUInstallDirs)\ninclude(CMakePackageConfigHelpers)\nset(_config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/'
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ')\ninstall(TARGETS '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ' EXPORT '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield 'Targets\n    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}\n    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})\ninstall(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})\ninstall(EXPORT '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield 'Targets NAMESPACE '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield ':: DESTINATION ${_config_dir})\nexport(EXPORT '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield 'Targets NAMESPACE '
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield '::\n    FILE ${CMAKE_CURRENT_BINARY_DIR}/'
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield 'Targets.cmake)\nconfigure_package_config_file(cmake/Config.cmake.in\n    ${CMAKE_CURRENT_BINARY_DIR}/'
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield 'Config.cmake INSTALL_DESTINATION ${_config_dir})\nwrite_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/'
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield 'ConfigVersion.cmake\n    COMPATIBILITY SameMajorVersion)\ninstall(FILES ${CMAKE_CURRENT_BINARY_DIR}/'
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield 'Config.cmake\n    ${CMAKE_CURRENT_BINARY_DIR}/'
    yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
    yield 'ConfigVersion.cmake DESTINATION ${_config_dir})\n'

blocks = {}
debug_info = '1=19&2=21&3=23&4=29&6=31&11=33&12=35&13=41&14=43&15=45&18=47&22=49&23=51&27=55&28=59&29=63&31=65&32=67&34=69&35=71'
