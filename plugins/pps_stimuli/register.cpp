// Stimulus sources for peripersonal-space learning.
#include "object_thrower.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::ObjectThrower>();
}
