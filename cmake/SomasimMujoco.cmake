# MuJoCo, an optional benchmark peer only (Debian libmujoco-dev): when found, the target
# somasim_mujoco links it and the MJCF exporter's load test and bench_mujoco_peer are built.
# Nothing of somasim itself links it.
find_path(MUJOCO_INCLUDE_DIR mujoco/mujoco.h)
find_library(MUJOCO_LIBRARY mujoco)
if(MUJOCO_INCLUDE_DIR AND MUJOCO_LIBRARY)
  add_library(somasim_mujoco INTERFACE)
  target_include_directories(somasim_mujoco SYSTEM INTERFACE ${MUJOCO_INCLUDE_DIR})
  target_link_libraries(somasim_mujoco INTERFACE ${MUJOCO_LIBRARY})
  message(STATUS "MuJoCo (benchmark peer): ${MUJOCO_LIBRARY}")
else()
  message(STATUS "MuJoCo not found: its load test and benchmark are skipped (libmujoco-dev)")
endif()
