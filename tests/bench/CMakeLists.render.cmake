# Render benchmark (included from tests/bench/CMakeLists.txt): one 320 x 240 view of the iCub
# upper body through SceneRenderer (RGB, with depth / ids / the drew-no-pixel check as variants)
# vs clear + draw + RGB read-back of the same triangles by a trivial shader.
add_executable(bench_render_view ${CMAKE_CURRENT_LIST_DIR}/bench_render_view.cpp)
target_link_libraries(bench_render_view PRIVATE somasim::render benchmark::benchmark_main)
target_compile_definitions(bench_render_view PRIVATE SOMASIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
