# Installs the build tree into a temporary prefix outside the source and build trees, moves the installation,
# and checks that it works there on its own: the installed program finds the moved data (not the build-time
# prefix nor the source tree, and with its data hidden it fails rather than fall back to the source tree), a
# downstream project finds craterkit with find_package and links its libraries, a chronology-only project
# needs neither HDF5 nor OpenMP, and the installed Python package (when built) imports and computes.
# Invoked by CTest with -DBUILD_DIR, -DCONSUMER_DIR, -DCHRONOLOGY_CONSUMER_DIR, -DSCRATCH (consumer builds),
# the compiler and flags of the build (-DCONSUMER_CXX_COMPILER, -DCONSUMER_CXX_FLAGS, -DCONSUMER_LINKER_FLAGS:
# sanitizer flags and runtimes belong to one compiler) and, for the Python package, -DPYTHON=<interpreter>
# -DPYTHON_SUBDIR=<its folder under the prefix>.
file(REMOVE_RECURSE ${SCRATCH})
file(MAKE_DIRECTORY ${SCRATCH})
# The installation lives outside the source and build trees (in the temporary folder), so that a binary
# there can never be taken for one of the build tree: only its own installation can give it data.
if(DEFINED ENV{TMPDIR} AND IS_DIRECTORY "$ENV{TMPDIR}")
  set(outside "$ENV{TMPDIR}")
else()
  set(outside "/tmp")
endif()
string(RANDOM LENGTH 10 tag)
set(root "${outside}/craterkit-install-check-${tag}")
macro(fail message_text)
  file(REMOVE_RECURSE "${root}")
  message(FATAL_ERROR "${message_text}")
endmacro()
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${root}/staged
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  fail("cmake --install failed (${rc})")
endif()
# The configured prefix (staged) no longer exists after the move: nothing may depend on it.
file(RENAME ${root}/staged ${root}/moved)
set(prefix ${root}/moved)
foreach(f bin/craterkit share/craterkit/scaling/jutzi2022_ryugu.toml share/doc/craterkit/LICENSE)
  if(NOT EXISTS ${prefix}/${f})
    fail("the installation lacks ${f}")
  endif()
endforeach()

# Runs the installed program from a folder outside the source and build trees, without CRATERKIT_DATA_DIR.
function(run_installed out_var)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=CRATERKIT_DATA_DIR ${prefix}/bin/craterkit ${ARGN}
                  WORKING_DIRECTORY ${SCRATCH} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    fail("installed craterkit ${ARGN} failed (${rc}):\n${out}\n${err}")
  endif()
  set(${out_var} "${out}" PARENT_SCOPE)
endfunction()

run_installed(listing list --json)
string(JSON data_dir GET "${listing}" data_directory)
string(JSON origin GET "${listing}" data_origin)
file(REAL_PATH ${prefix}/share/craterkit expected_dir)
file(REAL_PATH ${data_dir} data_dir)
if(NOT data_dir STREQUAL expected_dir OR NOT origin STREQUAL "installation")
  fail("the moved installation uses the data in ${data_dir} (${origin}), not ${expected_dir}")
endif()
string(JSON n_sets LENGTH "${listing}" constant_sets)
if(n_sets LESS 10)
  fail("the installed program lists ${n_sets} constant sets:\n${listing}")
endif()
run_installed(scaled scale --params jutzi2022_ryugu --body ryugu --impactor-radius 0.056 --impactor-density 2700
              --velocity 2000 --json)
string(JSON crater_radius GET "${scaled}" crater_radius)
if(crater_radius LESS 5 OR crater_radius GREATER 20)
  fail("installed craterkit scale gives a crater radius of ${crater_radius} m")
endif()
run_installed(aged age ${prefix}/share/craterkit/craters/ryugu_synthetic_unit.scc --params jutzi2022_ryugu
              --body ryugu --cohesion 0.05 --json)
# The report finds its plotting script under the moved prefix: its figures are drawn, or skipped only for want
# of matplotlib, never for want of the script.
run_installed(reported report --radii ${prefix}/share/craterkit/radii/cohesion_size_coarse.csv
              --out ${SCRATCH}/report --quiet)
file(READ ${SCRATCH}/report/report.md report_md)
if(report_md MATCHES "plot_report.py not found" OR NOT EXISTS ${prefix}/share/craterkit/scripts/plot_report.py)
  fail("the installed report does not find its plotting script:\n${report_md}")
endif()

foreach(consumer ${CONSUMER_DIR} ${CHRONOLOGY_CONSUMER_DIR})
  get_filename_component(name ${consumer} NAME)
  set(extra "")
  if(name STREQUAL "consumer_chronology")
    set(extra -DCMAKE_DISABLE_FIND_PACKAGE_HDF5=ON -DCMAKE_DISABLE_FIND_PACKAGE_OpenMP=ON)
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${consumer} -B ${SCRATCH}/build_${name} -DCMAKE_PREFIX_PATH=${prefix}
                          -DCMAKE_CXX_COMPILER=${CONSUMER_CXX_COMPILER} "-DCMAKE_CXX_FLAGS=${CONSUMER_CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_LINKER_FLAGS}"
                          ${extra}
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    fail("configuring ${name} with find_package(craterkit) failed (${rc})")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${SCRATCH}/build_${name} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    fail("building ${name} failed (${rc})")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E env CRATERKIT_DATA_DIR=${prefix}/share/craterkit
                          ${SCRATCH}/build_${name}/${name} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    fail("${name} failed (${rc})")
  endif()
endforeach()

if(PYTHON)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=CRATERKIT_DATA_DIR PYTHONPATH=${prefix}/${PYTHON_SUBDIR}
                          ${PYTHON} -c
                          "import craterkit, os; d = os.path.realpath(craterkit.data_directory()); assert d == os.path.realpath('${expected_dir}'), d; assert 'jutzi2022_ryugu' in craterkit.constant_set_names(); print(craterkit.__file__, d)"
                  WORKING_DIRECTORY ${SCRATCH} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "${prefix}")
    fail("the installed Python package failed (${rc}):\n${out}\n${err}")
  endif()
endif()

# With its data hidden, the installed program must not fall back to the source tree of its build.
file(RENAME ${prefix}/share/craterkit ${prefix}/share/craterkit.hidden)
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=CRATERKIT_DATA_DIR ${prefix}/bin/craterkit list --json
                WORKING_DIRECTORY ${root} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 AND out MATCHES "source tree")
  fail("with its data hidden, the installed program used the source tree:\n${out}")
endif()
if(NOT rc EQUAL 0 AND NOT err MATCHES "data directory not found")
  fail("with its data hidden, the installed program failed without saying why (${rc}):\n${err}")
endif()
file(REMOVE_RECURSE "${root}")
