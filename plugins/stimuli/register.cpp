// Stimulus sources.
#include "taxel_thrower.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::TaxelThrower>();
}
