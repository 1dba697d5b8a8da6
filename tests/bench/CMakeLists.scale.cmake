# Benchmark of PPS at scale (included from tests/bench/CMakeLists.txt): the pps_scale scene
# (4,245-taxel skin, world at 1 kHz) per tick with and without the learner, and skin + learner
# alone at 20 Hz.
add_executable(bench_pps_scale ${CMAKE_CURRENT_LIST_DIR}/bench_pps_scale.cpp)
target_link_libraries(bench_pps_scale PRIVATE somasim::framework somasim::robot somasim::pps
  benchmark::benchmark_main)
target_compile_definitions(bench_pps_scale PRIVATE SOMASIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
add_dependencies(bench_pps_scale somasim_plugin_bullet_world somasim_plugin_skin
  somasim_plugin_pps_stimuli somasim_plugin_pps)
