// Controllers: joint-space trajectories, Cartesian velocity control of any point of a chain,
// and a mux merging several controllers' joint commands.
#include "cartesian_velocity.hpp"
#include "joint_command_mux.hpp"
#include "joint_trajectory.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::JointTrajectoryController>();
  registrar.add<somasim::plugins::CartesianVelocity>();
  registrar.add<somasim::plugins::JointCommandMux>();
}
