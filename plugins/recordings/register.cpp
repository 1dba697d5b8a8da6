// Recordings: yarpdatadumper logs of a real robot replayed onto ports on the simulated clock
// (skin contact lists, joint encoders, camera images).
#include "yarp_encoder_replay.hpp"
#include "yarp_image_replay.hpp"
#include "yarp_skin_replay.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::YarpSkinReplay>();
  registrar.add<somasim::plugins::YarpEncoderReplay>();
  registrar.add<somasim::plugins::YarpImageReplay>();
}
