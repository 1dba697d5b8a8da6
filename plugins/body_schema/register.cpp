// Body-schema plugins: the particle filter, the reaching controller, the bimanual report.
#include "bimanual_report.hpp"
#include "body_schema_filter.hpp"
#include "reach_controller.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::BodySchemaFilter>();
  registrar.add<somasim::plugins::ReachController>();
  registrar.add<somasim::plugins::BimanualReport>();
}
