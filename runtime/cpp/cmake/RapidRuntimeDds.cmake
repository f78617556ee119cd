# rapid_runtime_cpp_add_dds(<target> PACKAGE <pkg>)
#
# Compiles the runtime's Fast DDS layer (RAPID_RUNTIME_CPP_DDS_DIR) into <target> against
# the asset package <pkg> (found with find_package(<pkg>) by the caller: its ::rapid types
# and Fast DDS topic types). The layer includes "rapid_runtime_dds_types.hpp", written
# here to include <pkg>'s headers: every asset package declares the same ::rapid types,
# so the layer is compiled once per bridge, never into a shared library of its own.
function(rapid_runtime_cpp_add_dds target)
    cmake_parse_arguments(ARG "" "PACKAGE" "" ${ARGN})
    if(NOT ARG_PACKAGE)
        message(FATAL_ERROR "rapid_runtime_cpp_add_dds(${target}): PACKAGE <asset package> is required")
    endif()
    find_package(fastcdr REQUIRED)
    find_package(fastrtps REQUIRED)
    set(_types_dir ${CMAKE_CURRENT_BINARY_DIR}/${target}_rapid_types)
    file(WRITE ${_types_dir}/rapid_runtime_dds_types.hpp.in
        "// written by rapid_runtime_cpp_add_dds: the asset package the DDS layer is built with\n"
        "#include <${ARG_PACKAGE}/types.hpp>\n#include <${ARG_PACKAGE}/topics.hpp>\n"
        "#include <${ARG_PACKAGE}/cdr.hpp>\n")
    configure_file(${_types_dir}/rapid_runtime_dds_types.hpp.in ${_types_dir}/rapid_runtime_dds_types.hpp COPYONLY)
    target_sources(${target} PRIVATE
        ${RAPID_RUNTIME_CPP_DDS_DIR}/src/messages.cpp
        ${RAPID_RUNTIME_CPP_DDS_DIR}/src/node.cpp
        ${RAPID_RUNTIME_CPP_DDS_DIR}/src/security.cpp
        ${RAPID_RUNTIME_CPP_DDS_DIR}/src/bridge.cpp
        ${RAPID_RUNTIME_CPP_DDS_DIR}/src/telemetry.cpp
        ${RAPID_RUNTIME_CPP_DDS_DIR}/src/simulate.cpp
        ${RAPID_RUNTIME_CPP_DDS_DIR}/src/program.cpp)
    target_include_directories(${target} PRIVATE ${_types_dir} ${RAPID_RUNTIME_CPP_DDS_DIR}/include)
    target_link_libraries(${target} PRIVATE rapid_runtime_cpp::core ${ARG_PACKAGE}::${ARG_PACKAGE} fastrtps fastcdr)
endfunction()

# rapid_runtime_cpp_add_cmd(<target> PACKAGE <pkg> [BRIDGE_DIR <dir>])
#
# The ground-side client as a program (rapid_cmd, dds/include/rapid_runtime/dds/cmd.hpp),
# built with <pkg>'s ::rapid types (any asset package holds them all: the dictionary comes
# from the asset's live CommandConfig). With BRIDGE_DIR (a generated package's bridge/
# folder) the asset's tables and Fast DDS profiles are built in: --asset, --qos and the
# ranges and defaults the CommandConfig does not carry come from them.
function(rapid_runtime_cpp_add_cmd target)
    cmake_parse_arguments(ARG "" "PACKAGE;BRIDGE_DIR" "" ${ARGN})
    if(NOT ARG_PACKAGE)
        message(FATAL_ERROR "rapid_runtime_cpp_add_cmd(${target}): PACKAGE <asset package> is required")
    endif()
    find_package(fastcdr REQUIRED)
    find_package(fastrtps REQUIRED)
    set(_dir ${CMAKE_CURRENT_BINARY_DIR}/${target}_rapid_types)
    file(WRITE ${_dir}/rapid_runtime_dds_types.hpp.in
        "// written by rapid_runtime_cpp_add_cmd: the asset package the client is built with\n"
        "#include <${ARG_PACKAGE}/types.hpp>\n#include <${ARG_PACKAGE}/topics.hpp>\n"
        "#include <${ARG_PACKAGE}/cdr.hpp>\n")
    configure_file(${_dir}/rapid_runtime_dds_types.hpp.in ${_dir}/rapid_runtime_dds_types.hpp COPYONLY)
    if(ARG_BRIDGE_DIR)
        file(WRITE ${_dir}/main.cpp.in
            "// written by rapid_runtime_cpp_add_cmd: rapid_cmd with ${ARG_PACKAGE}'s tables and profiles\n"
            "#include <rapid_runtime/dds/cmd.hpp>\n#include \"handlers.hpp\"\n"
            "int main(int argc, char** argv) {\n"
            "    return ::rapid_runtime::dds::run_cmd(argc, argv, {&::${ARG_PACKAGE}::bridge::tables(), "
            "::${ARG_PACKAGE}::bridge::PROFILES_XML});\n}\n")
        set(_extra ${ARG_BRIDGE_DIR}/tables.cpp ${ARG_BRIDGE_DIR}/profiles.cpp)
    else()
        file(WRITE ${_dir}/main.cpp.in
            "// written by rapid_runtime_cpp_add_cmd: rapid_cmd, any asset (--asset, --qos)\n"
            "#include <rapid_runtime/dds/cmd.hpp>\n"
            "int main(int argc, char** argv) { return ::rapid_runtime::dds::run_cmd(argc, argv, {}); }\n")
        set(_extra)
    endif()
    configure_file(${_dir}/main.cpp.in ${_dir}/main.cpp COPYONLY)
    add_executable(${target} ${_dir}/main.cpp ${_extra}
        ${RAPID_RUNTIME_CPP_DDS_DIR}/src/messages.cpp
        ${RAPID_RUNTIME_CPP_DDS_DIR}/src/node.cpp
        ${RAPID_RUNTIME_CPP_DDS_DIR}/src/security.cpp
        ${RAPID_RUNTIME_CPP_DDS_DIR}/src/client.cpp
        ${RAPID_RUNTIME_CPP_DDS_DIR}/src/cmd.cpp)
    set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
    target_compile_features(${target} PRIVATE cxx_std_17)
    target_include_directories(${target} PRIVATE ${_dir} ${RAPID_RUNTIME_CPP_DDS_DIR}/include ${ARG_BRIDGE_DIR})
    target_link_libraries(${target} PRIVATE rapid_runtime_cpp::core ${ARG_PACKAGE}::${ARG_PACKAGE} fastrtps fastcdr)
endfunction()
