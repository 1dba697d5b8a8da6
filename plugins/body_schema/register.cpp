// Body-schema plugins: the particle filter and the reaching controller.
#include "body_schema_filter.hpp"
#include "reach_controller.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::BodySchemaFilter>();
  registrar.add<somasim::plugins::ReachController>();
}
