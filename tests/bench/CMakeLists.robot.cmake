# Benchmark of somasim_robot (included from tests/bench/CMakeLists.txt).
# Requires find_package(benchmark) to have been called.
add_executable(bench_kinematics ${CMAKE_CURRENT_LIST_DIR}/bench_kinematics.cpp)
target_link_libraries(bench_kinematics PRIVATE somasim::robot benchmark::benchmark_main)
target_compile_definitions(bench_kinematics PRIVATE SOMASIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
