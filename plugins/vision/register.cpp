// Vision plugins: what the eyes make of their images.
#include "gaze_controller.hpp"
#include "marker_tracker.hpp"
#include "object_tracker.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::MarkerTracker>();
  registrar.add<somasim::plugins::GazeController>();
  registrar.add<somasim::plugins::ObjectTracker>();
}
