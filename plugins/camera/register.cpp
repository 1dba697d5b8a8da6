// Camera plugins.
#include "camera_plugin.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::CameraPlugin>();
}
