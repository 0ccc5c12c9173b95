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

# pdeface_write_layering(<file>): our targets as "target|folder|dep;dep;..." lines (folder relative to the
# source tree, deps the targets each links, aliases resolved), for tests/layering/check_layers.cmake. Called
# once every target is defined.
function(pdeface_write_layering file)
  get_property(targets GLOBAL PROPERTY PDEFACE_LIBRARIES)
  list(APPEND targets pdeface)
  set(lines "")
  foreach(target IN LISTS targets)
    if(target STREQUAL "pdeface_all")
      continue() # the package's umbrella: links everything by design
    endif()
    get_target_property(dir ${target} SOURCE_DIR)
    file(RELATIVE_PATH folder ${PROJECT_SOURCE_DIR} ${dir})
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "INTERFACE_LIBRARY")
      get_target_property(links ${target} INTERFACE_LINK_LIBRARIES)
    else()
      get_target_property(links ${target} LINK_LIBRARIES)
    endif()
    set(deps "")
    foreach(link IN LISTS links)
      if(TARGET ${link})
        get_target_property(aliased ${link} ALIASED_TARGET)
        if(aliased)
          set(link ${aliased})
        endif()
        list(APPEND deps ${link})
      endif()
    endforeach()
    list(JOIN deps ";" deps)
    string(APPEND lines "${target}|${folder}|${deps}\n")
  endforeach()
  file(WRITE ${file} "${lines}")
endfunction()
