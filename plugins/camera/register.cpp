// Camera plugins.
#include "camera_plugin.hpp"
#include "spectator.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::CameraPlugin>();
  registrar.add<somasim::plugins::Spectator>();
}
