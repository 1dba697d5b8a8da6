# Camera-in-the-world benchmark (included from tests/bench/CMakeLists.txt): real-time factor of
# configs/ball_on_forearm_camera.yaml vs configs/ball_on_forearm.yaml, whole `somasim run`.
add_executable(bench_camera_rtf ${CMAKE_CURRENT_LIST_DIR}/bench_camera_rtf.cpp)
target_link_libraries(bench_camera_rtf PRIVATE benchmark::benchmark_main
                                               nlohmann_json::nlohmann_json)
target_compile_definitions(bench_camera_rtf PRIVATE
  SOMASIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}" SOMASIM_BIN="$<TARGET_FILE:somasim>")
add_dependencies(bench_camera_rtf somasim somasim_plugin_bullet_world somasim_plugin_skin
                 somasim_plugin_stimuli somasim_plugin_camera)
