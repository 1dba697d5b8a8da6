# Hypothesis-batch benchmark (included from tests/bench/CMakeLists.txt): 200 forearm + hand
# hypotheses in both eyes, tiled with one read-back per worker, vs its bare floor (the same draws
# and read-back, no extraction) and vs one full SceneRenderer render and read-back per hypothesis
# and eye.
add_executable(bench_hypothesis_batch ${CMAKE_CURRENT_LIST_DIR}/bench_hypothesis_batch.cpp)
target_link_libraries(bench_hypothesis_batch PRIVATE somasim::render benchmark::benchmark_main)
