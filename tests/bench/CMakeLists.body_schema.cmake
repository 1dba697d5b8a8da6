# Body-schema filter step benchmark (included from tests/bench/CMakeLists.txt): M = 200 and 2000
# hypotheses of the right hand in both eyes, against the bare render + read-back of the same
# hypotheses.
add_executable(bench_body_schema ${CMAKE_CURRENT_LIST_DIR}/bench_body_schema.cpp)
target_link_libraries(bench_body_schema PRIVATE somasim::body_schema opencv_imgproc
  benchmark::benchmark_main)
target_compile_definitions(bench_body_schema PRIVATE SOMASIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
