# cmake -P driver of the out_of_tree_plugin test (see CMakeLists.txt):
#   1. cmake --install <build> --prefix <work>/prefix
#   2. configure + build example/ against the prefix (CMAKE_PREFIX_PATH)
#   3. run <prefix>/bin/somasim on an experiment that loads the example by path and wires it to
#      the test plugins' counter
#   4. check the CSV and metrics.json it wrote
#   5. `somasim plugin new`: the template builds against the prefix, is indexed, passes its
#      harness test and is described by the installed somasim
#   6. the example builds against the build tree as well (find_package with the build folder)
foreach(var SOMASIM_BUILD_DIR EXAMPLE_DIR WORK_DIR TEST_PLUGIN_DIR GENERATOR CXX_COMPILER CTEST)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "missing -D${var}=...")
  endif()
endforeach()

function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${step} failed (${rc}):\n${ARGN}\n--- stdout\n${out}\n--- stderr\n${err}")
  endif()
  set(run_stdout "${out}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
set(example_build ${WORK_DIR}/example-build)
set(run_dir ${WORK_DIR}/run)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

run("install" ${CMAKE_COMMAND} --install ${SOMASIM_BUILD_DIR} --prefix ${prefix})
run("configure example" ${CMAKE_COMMAND} -S ${EXAMPLE_DIR} -B ${example_build} -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_BUILD_TYPE=Release)
run("build example" ${CMAKE_COMMAND} --build ${example_build})

set(library ${example_build}/plugins/libsomasim_low_pass.so)
foreach(file ${library} ${library}.index)
  if(NOT EXISTS ${file})
    message(FATAL_ERROR "the example did not produce ${file}")
  endif()
endforeach()

# tau = dt = 0.001 s gives a = 0.5 exactly: y_k = 1 - 0.5^(k+1) for a unit step (gain 1), every
# value exact in binary, so the CSV can be compared byte for byte.
file(WRITE ${WORK_DIR}/exp.yaml "experiment: out_of_tree
duration_s: 0.005
plugin_libraries: [${library}]
nodes:
  u: {plugin: counter, params: {start: 1, increment: 0}}
  y: {plugin: low_pass, params: {time_constant_s: 0.001}, inputs: {in: u.value}}
record: [y.out]
")
set(somasim ${prefix}/bin/somasim)
run("describe" ${somasim} --plugin-path ${example_build}/plugins plugins describe low_pass)
if(NOT run_stdout MATCHES "time_constant_s +a number \\[s\\], default 0.1, range \\[0, inf\\]")
  message(FATAL_ERROR "unexpected 'plugins describe low_pass' output:\n${run_stdout}")
endif()
run("run" ${somasim} --plugin-path ${TEST_PLUGIN_DIR} run ${WORK_DIR}/exp.yaml --out ${run_dir}
    --quiet)

file(READ ${run_dir}/y.out.csv csv)
set(expected_csv "time [s],value\n0,0.5\n0.001,0.75\n0.002,0.875\n0.003,0.9375\n0.004,0.96875\n")
if(NOT csv STREQUAL expected_csv)
  message(FATAL_ERROR "y.out.csv:\n${csv}\nexpected:\n${expected_csv}")
endif()

file(READ ${run_dir}/metrics.json metrics)
string(JSON status GET "${metrics}" status)
string(JSON final GET "${metrics}" nodes y final_output)
string(JSON plugin_api GET "${metrics}" versions plugin_interface)
if(NOT status STREQUAL "completed" OR NOT final STREQUAL "0.96875")
  message(FATAL_ERROR "metrics.json: status '${status}', final_output '${final}':\n${metrics}")
endif()
# 5. The template.
set(somasim_new ${prefix}/bin/somasim)
run("plugin new" ${somasim_new} plugin new my_gain --dir ${WORK_DIR}/my_gain)
run("configure template" ${CMAKE_COMMAND} -S ${WORK_DIR}/my_gain -B ${WORK_DIR}/my_gain/build
    -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_BUILD_TYPE=Release)
run("build template" ${CMAKE_COMMAND} --build ${WORK_DIR}/my_gain/build)
foreach(file libsomasim_my_gain.so libsomasim_my_gain.so.index)
  if(NOT EXISTS ${WORK_DIR}/my_gain/build/plugins/${file})
    message(FATAL_ERROR "the template did not produce plugins/${file}")
  endif()
endforeach()
run("template's harness test" ${CTEST} --test-dir ${WORK_DIR}/my_gain/build
    --output-on-failure)
if(NOT run_stdout MATCHES "100% tests passed, 0 tests failed out of 1")
  message(FATAL_ERROR "the template's test did not run:\n${run_stdout}")
endif()
run("template's test binary" ${WORK_DIR}/my_gain/build/test_my_gain)
if(NOT run_stdout MATCHES "PASSED  \\] 2 tests")
  message(FATAL_ERROR "the template's harness tests did not all run:\n${run_stdout}")
endif()
run("describe template" ${somasim_new} --plugin-path ${WORK_DIR}/my_gain/build/plugins
    plugins describe my_gain)
if(NOT run_stdout MATCHES "gain +a number, default 1")
  message(FATAL_ERROR "unexpected 'plugins describe my_gain' output:\n${run_stdout}")
endif()

# 6. The example against the build tree.
run("configure example (build tree)" ${CMAKE_COMMAND} -S ${EXAMPLE_DIR}
    -B ${WORK_DIR}/example-build-tree -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    -DCMAKE_PREFIX_PATH=${SOMASIM_BUILD_DIR} -DCMAKE_BUILD_TYPE=Release)
run("build example (build tree)" ${CMAKE_COMMAND} --build ${WORK_DIR}/example-build-tree)
if(NOT EXISTS ${WORK_DIR}/example-build-tree/plugins/libsomasim_low_pass.so.index)
  message(FATAL_ERROR "the example built against the build tree was not indexed")
endif()

message(STATUS "out-of-tree plugin OK (${plugin_api}, final_output ${final})")
