# Benchmark of somasim_pps (included from tests/bench/CMakeLists.txt).
# Requires find_package(benchmark) to have been called.
add_executable(bench_pps ${CMAKE_CURRENT_LIST_DIR}/bench_pps.cpp)
target_link_libraries(bench_pps PRIVATE somasim::pps benchmark::benchmark_main)
