// Peripersonal-space plugins.
#include "pps_learner.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::PpsLearner>();
}
