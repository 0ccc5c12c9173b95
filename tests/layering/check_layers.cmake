# The one-way layering, checked over the include graph and the link graph (ctest: Layering.*):
#
#   apps, python (4) → pipeline (3) → formats (2) → modules (1) → core (0)
#
# A file may include the headers of its own layer and of the layers below, never above: nothing under
# modules/ includes pdeface/formats or a format's headers (pdeface/ply, pdeface/pdef, ...), nothing under
# formats/ includes pdeface/pipeline, and core includes core alone. Each library target may link targets of
# its own layer and below. A header's layer is the folder that provides it (<folder>/include/pdeface/<name>
# or <folder>/internal/pdeface/<name>); a target's is the folder that defines it. The headers in a formats
# folder's internal/ (what several formats share: pdeface/openmesh_io/, pdeface/draco/detail.hpp) are not
# installed and not an API: only files under formats/ include them.
#
# cmake -DSOURCE=<source tree> [-DGRAPH=<build>/layering.txt] -P check_layers.cmake
# GRAPH (written at configure time by pdeface_write_layering): "target|folder|dep;dep;..." per line.
cmake_minimum_required(VERSION 3.25)
if(NOT SOURCE)
  message(FATAL_ERROR "check_layers.cmake: -DSOURCE=<source tree> is required")
endif()

# The layer of a path relative to the source tree, or -1 when it is in none (tests, benchmarks, fuzz).
function(layer_of path out)
  if(path MATCHES "^modules/core(/|$)")
    set(${out} 0 PARENT_SCOPE)
  elseif(path MATCHES "^modules/")
    set(${out} 1 PARENT_SCOPE)
  elseif(path MATCHES "^formats(/|$)")
    set(${out} 2 PARENT_SCOPE)
  elseif(path MATCHES "^pipeline(/|$)")
    set(${out} 3 PARENT_SCOPE)
  elseif(path MATCHES "^(apps|python)/")
    set(${out} 4 PARENT_SCOPE)
  else()
    set(${out} -1 PARENT_SCOPE)
  endif()
endfunction()
set(layer_names core modules formats pipeline apps)

# Which folder provides each pdeface/<name>/ header directory.
file(GLOB header_dirs LIST_DIRECTORIES true RELATIVE ${SOURCE}
     ${SOURCE}/modules/*/include/pdeface/* ${SOURCE}/modules/*/internal/pdeface/*
     ${SOURCE}/formats/include/pdeface/* ${SOURCE}/formats/*/include/pdeface/* ${SOURCE}/formats/*/internal/pdeface/*
     ${SOURCE}/pipeline/include/pdeface/*)
foreach(dir IN LISTS header_dirs)
  if(IS_DIRECTORY ${SOURCE}/${dir})
    get_filename_component(name ${dir} NAME)
    layer_of(${dir} layer)
    set(header_layer_${name} ${layer})
    set(header_dir_${name} ${dir})
  endif()
endforeach()

# The headers private to formats/, as included ("pdeface/openmesh_io/openmesh_io.hpp").
file(GLOB_RECURSE formats_internal RELATIVE ${SOURCE} ${SOURCE}/formats/*/internal/pdeface/*)
list(TRANSFORM formats_internal REPLACE "^formats/[^/]+/internal/" "")

set(failures "")
set(files_checked 0)
set(includes_checked 0)
file(GLOB_RECURSE sources RELATIVE ${SOURCE}
     ${SOURCE}/modules/*.cpp ${SOURCE}/modules/*.hpp ${SOURCE}/formats/*.cpp ${SOURCE}/formats/*.hpp
     ${SOURCE}/pipeline/*.cpp ${SOURCE}/pipeline/*.hpp ${SOURCE}/apps/*.cpp ${SOURCE}/apps/*.hpp
     ${SOURCE}/python/*.cpp ${SOURCE}/python/*.hpp)
foreach(file IN LISTS sources)
  layer_of(${file} layer)
  math(EXPR files_checked "${files_checked} + 1")
  file(STRINGS ${SOURCE}/${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]pdeface/")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[\"<]pdeface/([^/\">]+).*$" "\\1" name "${line}")
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[\"<](pdeface/[^\">]+).*$" "\\1" header "${line}")
    math(EXPR includes_checked "${includes_checked} + 1")
    if(header IN_LIST formats_internal AND NOT file MATCHES "^formats/")
      list(APPEND failures "${file} includes ${header}, which is internal to formats/")
    elseif(NOT DEFINED header_layer_${name})
      list(APPEND failures "${file}: includes pdeface/${name}/, which no folder provides")
    elseif(header_layer_${name} GREATER layer)
      list(GET layer_names ${layer} from)
      list(GET layer_names ${header_layer_${name}} to)
      list(APPEND failures
           "${file} (${from}) includes pdeface/${name}/ (${to}, ${header_dir_${name}}): an arrow pointing up")
    endif()
  endforeach()
endforeach()

set(links_checked 0)
if(GRAPH)
  file(STRINGS ${GRAPH} graph)
  foreach(entry IN LISTS graph)
    string(REPLACE "|" ";" fields "${entry}")
    list(GET fields 0 target)
    list(GET fields 1 folder)
    list(LENGTH fields n)
    set(deps "")
    if(n GREATER 2)
      list(SUBLIST fields 2 -1 deps)
    endif()
    set(folder_of_${target} ${folder})
    set(deps_of_${target} ${deps})
    list(APPEND targets ${target})
  endforeach()
  foreach(target IN LISTS targets)
    layer_of(${folder_of_${target}} layer)
    if(layer LESS 0)
      continue()
    endif()
    foreach(dep IN LISTS deps_of_${target})
      if(NOT DEFINED folder_of_${dep})
        continue() # not ours: a Debian package
      endif()
      math(EXPR links_checked "${links_checked} + 1")
      layer_of(${folder_of_${dep}} dep_layer)
      if(dep_layer GREATER layer)
        list(GET layer_names ${layer} from)
        list(GET layer_names ${dep_layer} to)
        list(APPEND failures "${target} (${from}, ${folder_of_${target}}) links ${dep} (${to}, "
                             "${folder_of_${dep}}): an arrow pointing up")
      endif()
    endforeach()
  endforeach()
endif()

if(failures)
  list(JOIN failures "\n  " text)
  message(FATAL_ERROR "the layering apps → pipeline → formats → modules → core is broken:\n  ${text}")
endif()
message(STATUS "layering: ${includes_checked} includes in ${files_checked} files and ${links_checked} links "
               "between our targets all point down")
