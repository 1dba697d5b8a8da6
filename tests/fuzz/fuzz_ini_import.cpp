// libFuzzer target: the original iCub `taxels2D_*.ini` learned files. Bad input must be an
// InputError naming the line.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "somasim/error.hpp"
#include "somasim/pps/ini_import.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    (void)somasim::pps::parse_taxels2d_ini(in, "<fuzz>");
  } catch (const somasim::InputError&) {
  }
  return 0;
}
