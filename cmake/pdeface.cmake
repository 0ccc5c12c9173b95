# pdeface_add_library(<name> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Defines pdeface_<name> with the alias pdeface::<name> (exported as pdeface::<name> too); headers live in
# include/pdeface/<name>/ and are installed with it.
function(pdeface_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(pdeface_${name} ${ARG_SOURCES})
  add_library(pdeface::${name} ALIAS pdeface_${name})
  target_include_directories(pdeface_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>)
  target_link_libraries(pdeface_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  pdeface_warnings(pdeface_${name})
  pdeface_install(pdeface_${name} ${name})
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# pdeface_install(<target> <export name>): the target in the package's export set (pdeface::<export name>),
# without headers: internal targets that the installed libraries link (their headers stay private).
function(pdeface_install target export_name)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name})
  install(TARGETS ${target} EXPORT pdefaceTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  set_property(GLOBAL APPEND PROPERTY PDEFACE_LIBRARIES ${target})
endfunction()

# Warnings for our own code (third-party headers come in as SYSTEM includes and stay quiet).
# -Wno-missing-field-initializers: designated initializers that leave defaulted members out
#   (`{.draco_bits = 14}`) are how options structs are meant to be used.
# -Wno-restrict: GCC 12 false positive inside std::string's operator+ at -O2 (GCC bug 105329).
function(pdeface_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                         -Wno-sign-conversion -Wno-missing-field-initializers
                         $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
endfunction()
