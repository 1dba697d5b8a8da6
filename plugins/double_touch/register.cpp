// Self-touch stimulus source for peripersonal-space learning (tactile-motor learning).
#include "double_touch.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::DoubleTouch>();
}
