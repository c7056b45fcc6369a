# run_install_test.cmake — `cmake --install` of a cdyn build into a fresh prefix, then
# configure, build and run tests/install/outside against it (cmake -P script; see
# tests/install/CMakeLists.txt for the variables).  Fails with one line per problem.
foreach(v BUILD_DIR SOURCE_DIR WORK_DIR GEO CONFIG)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_install_test.cmake: -D${v}= is missing")
  endif()
endforeach()

file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

run("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix} --config ${CONFIG})
foreach(f include/cdyn/mass_model.hpp include/cdyn/version.hpp include/cdyn/gmsh_mesh.hpp
          include/cdyn/fields_output.hpp lib/cmake/cdyn/cdynConfig.cmake lib/cmake/cdyn/cdynConfigVersion.cmake
          bin/cdyn lib/cdyn/libcdyn_gmsh.so)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "the install tree lacks ${f}")
  endif()
endforeach()
# The package must not point back into the build or source tree (it would then work
# here and nowhere else).
file(GLOB_RECURSE cmake_files ${prefix}/lib/cmake/cdyn/*.cmake)
foreach(f ${cmake_files})
  file(READ ${f} text)
  foreach(tree ${BUILD_DIR} ${SOURCE_DIR})
    string(FIND "${text}" "${tree}/" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${f} refers to ${tree}")
    endif()
  endforeach()
endforeach()

# The installed program runs on its own (default scene and plot scripts compiled in),
# from a directory outside the build and source trees.
run("the installed cdyn --version" ${prefix}/bin/cdyn --version)
if(NOT last_output MATCHES "^cdyn [0-9]+\\.[0-9]+\\.[0-9]+")
  message(FATAL_ERROR "the installed cdyn printed '${last_output}' for --version")
endif()
execute_process(COMMAND ${prefix}/bin/cdyn run --quiet --set mesh.n=4 --set time.T=0.01 --set output.plots=false
                        --out ${WORK_DIR}/installed_run
                WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK_DIR}/installed_run/summary.json)
  message(FATAL_ERROR "the installed cdyn did not run the default scene (${rc}): ${err}")
endif()

# The Python module (when built, -DPYTHON=...): installed under PREFIX/PYTHON_DIR, which
# is on the interpreter's own path for its default prefix (/usr/local on Debian), and
# imported from there alone it runs the default scene as the installed program does.
if(PYTHON)
  foreach(f __init__.py runs.py scenes.py)
    if(NOT EXISTS ${prefix}/${PYTHON_DIR}/cdyn/${f})
      message(FATAL_ERROR "the install tree lacks ${PYTHON_DIR}/cdyn/${f}")
    endif()
  endforeach()
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/${PYTHON_DIR} PYTHONDONTWRITEBYTECODE=1
                          ${PYTHON} ${SOURCE_DIR}/tests/install/check_python_module.py ${prefix}/${PYTHON_DIR}
                          ${DEFAULT_PREFIX}/${PYTHON_DIR} installed_run
                  WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the installed Python module failed (${rc}):\n${out}\n${err}")
  endif()
  message("${out}")
endif()

run("configuring the outside project" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/outside -B ${WORK_DIR}/build
    -DCMAKE_BUILD_TYPE=${CONFIG} -DCMAKE_PREFIX_PATH=${prefix} "-DCMAKE_EXE_LINKER_FLAGS=${LINK_FLAGS}")
run("building the outside project" ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run("running the outside project" ${WORK_DIR}/build/outside ${GEO} ${WORK_DIR}/fields)
message("${last_output}")

# β = 0.3090 to the 4 digits `cdyn wellposed` prints (tests/cli/CMakeLists.txt,
# cli_wellposed; the closed form of tests/unit/test_wellposedness.cpp gives it to 1e-13);
# the L-shape's area 3/4 (data/geo/lshape.geo), exact up to round-off in the sum of the
# cell areas (12 printed digits).
foreach(expected "N_W 281 N_H 200 dimKerB 81 N_g 81 beta 0.3090 satisfied yes" "area 0.750000000000"
                 "wrote ")
  string(FIND "${last_output}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the outside program did not print '${expected}'")
  endif()
endforeach()
# The mesh was read by the installed gmsh plugin (the package gives its path), not the
# build tree's.
string(FIND "${last_output}" "gmsh plugin ${prefix}/lib/cdyn/libcdyn_gmsh.so" at)
if(at EQUAL -1)
  message(FATAL_ERROR "the outside program did not read its mesh with the installed gmsh plugin")
endif()
if(NOT EXISTS ${WORK_DIR}/fields/fields.pvd)
  message(FATAL_ERROR "the outside program wrote no fields.pvd")
endif()
