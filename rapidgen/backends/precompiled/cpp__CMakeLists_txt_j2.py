# mypy: ignore-errors
# Template templates/cpp/CMakeLists.txt.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "17a4b6048e097d84a0e1266fee1c66c9a564cbac98f783833fa850a3b1f7c553"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'CMakeLists.txt.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_p = resolve('p')
    l_0_bridge = resolve('bridge')
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
    yield "_DIR set to this project's build folder.\n"
    if (undefined(name='bridge') if l_0_bridge is missing else l_0_bridge):
        pass
        yield "# The asset's bridge "
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield "_bridge (bridge/: the C++ RAPID runtime on these types) is\n# built too when find_package(rapid_runtime_cpp) finds the runtime (rapidgen's runtime/cpp;\n# rapid_runtime_cpp_DIR=<its build folder>, or installed); -D"
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_BRIDGE=OFF skips it.\n# -D'
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_CMD=ON adds '
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield "_cmd, the ground-side client (rapidgen cmd's words)\n# with this asset's tables and profiles built in.\n"
    yield 'cmake_minimum_required(VERSION 3.16)\nproject('
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
    if (undefined(name='bridge') if l_0_bridge is missing else l_0_bridge):
        pass
        yield '\noption('
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_BRIDGE "build '
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_bridge (needs rapid_runtime_cpp)" ON)\n# (off by default: a robot needs its bridge, not a commander)\noption('
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_CMD "build '
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_cmd, the ground-side client (needs rapid_runtime_cpp)" OFF)\nif('
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_BRIDGE)\n    find_package(rapid_runtime_cpp QUIET)\n    if(rapid_runtime_cpp_FOUND)\n        add_executable('
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_bridge\n            bridge/dispatch.cpp\n            bridge/handlers.cpp\n            bridge/main.cpp\n            bridge/profiles.cpp\n            bridge/tables.cpp)\n        set_target_properties('
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_bridge PROPERTIES CXX_EXTENSIONS OFF)\n        target_compile_features('
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_bridge PRIVATE cxx_std_17)\n        rapid_runtime_cpp_add_dds('
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_bridge PACKAGE '
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield ')\n        install(TARGETS '
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_bridge RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})\n        if('
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_CMD)\n            rapid_runtime_cpp_add_cmd('
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_cmd PACKAGE '
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '\n                BRIDGE_DIR ${CMAKE_CURRENT_SOURCE_DIR}/bridge)\n            install(TARGETS '
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_cmd RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})\n        endif()\n    else()\n        message(STATUS "'
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield ': rapid_runtime_cpp not found; '
        yield str(environment.getattr((undefined(name='p') if l_0_p is missing else l_0_p), 'package'))
        yield '_bridge is not built "\n                       "(set rapid_runtime_cpp_DIR to the runtime\'s build folder)")\n    endif()\nendif()\n'

blocks = {}
debug_info = '1=20&2=22&3=24&4=30&5=32&6=35&8=37&9=39&13=44&18=46&19=48&20=54&21=56&22=58&25=60&29=62&30=64&34=68&35=72&36=76&38=78&39=80&41=82&42=84&43=86&45=89&47=93&48=97&51=99&57=101&58=103&59=105&60=109&61=111&62=113&64=117&67=119'
