#include "pps_evaluator.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::PpsEvaluator>();
}
