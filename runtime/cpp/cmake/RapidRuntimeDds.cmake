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
