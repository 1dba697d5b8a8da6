// Proprioception: what the robot believes of its own body.
#include "believed_kinematics.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::BelievedKinematics>();
}
