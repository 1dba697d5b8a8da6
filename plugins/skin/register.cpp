// Skin plugins.
#include "skin_plugin.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::SkinPlugin>();
}
