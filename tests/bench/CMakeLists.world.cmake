# Benchmark of the bullet_world plugin (included from tests/bench/CMakeLists.txt): the iCub world
# stepped through the plugin vs raw btMultiBodyDynamicsWorld::stepSimulation of the same scene.
add_executable(bench_world ${CMAKE_CURRENT_LIST_DIR}/bench_world.cpp)
target_link_libraries(bench_world PRIVATE somasim::framework somasim::robot somasim_bullet_world_lib
  benchmark::benchmark_main)
target_compile_definitions(bench_world PRIVATE SOMASIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
add_dependencies(bench_world somasim_plugin_bullet_world)

# bullet_world beside MuJoCo on the moving-robot scene (only where MuJoCo, an optional benchmark
# peer, is installed).
if(TARGET somasim_mujoco)
  add_executable(bench_mujoco_peer ${CMAKE_CURRENT_LIST_DIR}/bench_mujoco_peer.cpp)
  target_link_libraries(bench_mujoco_peer PRIVATE somasim::framework somasim::robot
    somasim_mujoco benchmark::benchmark_main)
  target_compile_definitions(bench_mujoco_peer PRIVATE SOMASIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  add_dependencies(bench_mujoco_peer somasim_plugin_bullet_world)
endif()
