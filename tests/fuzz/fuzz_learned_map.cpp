// libFuzzer target: learned PPS map files (JSON, versions 1-3) through the reader that
// `pps_learner`'s `load` uses. Invalid JSON and invalid maps must both be InputErrors.
#include <cstddef>
#include <cstdint>
#include <string>

#include "somasim/error.hpp"
#include "somasim/pps/map_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)somasim::pps::parse_learned_parts(text, "<fuzz>");
  } catch (const somasim::InputError&) {
  }
  return 0;
}
