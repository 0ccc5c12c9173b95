# pdeface_add_library(<name> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Defines pdeface_<name> with the alias pdeface::<name>; headers live in include/pdeface/<name>/.
function(pdeface_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(pdeface_${name} ${ARG_SOURCES})
  add_library(pdeface::${name} ALIAS pdeface_${name})
  target_include_directories(pdeface_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>)
  target_link_libraries(pdeface_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  pdeface_warnings(pdeface_${name})
endfunction()

function(pdeface_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                         -Wno-sign-conversion)
endfunction()
