// Stimulus sources.
#include "ball_thrower.hpp"
#include "taxel_thrower.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::TaxelThrower>();
  registrar.add<somasim::plugins::BallThrower>();
}
