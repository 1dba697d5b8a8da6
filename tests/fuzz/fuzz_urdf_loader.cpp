// libFuzzer target: URDF text (urdfdom and the checks before it; meshes resolved against the
// repository's robot folder). Bad input must be an InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "somasim/error.hpp"
#include "somasim/robot/robot_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)somasim::robot::parse_urdf_robot_model(text, "<fuzz>", SOMASIM_FUZZ_ASSETS_DIR "/robots");
  } catch (const somasim::InputError&) {
  }
  return 0;
}
