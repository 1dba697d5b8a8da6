# Whole-process experiment benchmarks (included from tests/bench/CMakeLists.txt).
add_executable(bench_monte_carlo ${CMAKE_CURRENT_LIST_DIR}/bench_monte_carlo.cpp)
target_link_libraries(bench_monte_carlo PRIVATE benchmark::benchmark_main)
target_compile_definitions(bench_monte_carlo PRIVATE
  SOMASIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}" SOMASIM_BIN="$<TARGET_FILE:somasim>")
add_dependencies(bench_monte_carlo somasim somasim_plugin_pps somasim_plugin_stimuli)
