# Installs the build into a fresh prefix, then configures, builds and runs the consumer project against it,
# and imports the Python package from the prefix when the module was built.
# -DBUILD=<pdeface build dir> -DSOURCE=<tests/install/consumer> -DWORK=<scratch dir>
# [-DPYTHON=<interpreter> -DPYTHON_DIR=<package dir under the prefix> -DFACE=<a scan to read>]
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE} -B ${WORK}/build -DCMAKE_BUILD_TYPE=Release
                        -DCMAKE_PREFIX_PATH=${WORK}/prefix RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "configuring the consumer failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/build --parallel 2 RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "building the consumer failed (${rc})")
endif()
foreach(program consumer consumer_core)
  execute_process(COMMAND ${WORK}/build/${program} WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "${program} failed (${rc})")
  endif()
endforeach()
# The installed headers hold no third-party internals: no OpenMesh or Draco header is included by them.
file(GLOB_RECURSE headers ${WORK}/prefix/include/*.hpp)
foreach(h ${headers})
  file(STRINGS ${h} lines REGEX "#include <(OpenMesh|draco)/")
  if(lines)
    message(FATAL_ERROR "${h} includes a third-party internal header: ${lines}")
  endif()
endforeach()
# The Python package from the prefix alone: `import pdeface` and a scan read into numpy.
if(PYTHON)
  set(script "import pdeface, numpy, sys; m = pdeface.read(sys.argv[1]) if sys.argv[1:] else pdeface.Mesh(numpy.eye(3), [[0, 1, 2]]); print(pdeface.__file__, m.vertices.shape)")
  set(face_arg "")
  if(EXISTS "${FACE}")
    set(face_arg "${FACE}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${WORK}/prefix/${PYTHON_DIR} ${PYTHON} -c "${script}" ${face_arg}
                  WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  if(rc OR NOT out MATCHES "^${WORK}/prefix/")
    message(FATAL_ERROR "importing the installed Python package failed (${rc}): ${out}")
  endif()
  message(STATUS "installed Python package: ${out}")
endif()
file(REMOVE_RECURSE ${WORK})
