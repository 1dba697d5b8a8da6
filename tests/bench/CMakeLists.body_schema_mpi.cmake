# The body-schema filter step with its particles spread over MPI ranks (included from
# tests/bench/CMakeLists.txt); run under mpirun by scripts/bench_mpi.sh (1 and 2 ranks).
add_executable(bench_body_schema_mpi ${CMAKE_CURRENT_LIST_DIR}/bench_body_schema_mpi.cpp)
target_link_libraries(bench_body_schema_mpi PRIVATE somasim::body_schema opencv_imgproc fmt::fmt
  MPI::MPI_CXX)
target_compile_definitions(bench_body_schema_mpi PRIVATE SOMASIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
