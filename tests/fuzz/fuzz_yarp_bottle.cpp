// libFuzzer target: one data.log line's content as a YARP Bottle, then as an iCub skin contact
// list. Bad input must be a BottleSyntaxError; what parses must print back to text that parses
// to the same text again (a fixed point), whatever the bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "somasim/recordings/skin_contact_list.hpp"
#include "somasim/recordings/yarp_bottle.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace somasim::recordings;
  const std::string text(reinterpret_cast<const char*>(data), size);
  BottleList bottle;
  try {
    bottle = parse_bottle(text);
  } catch (const BottleSyntaxError& e) {
    if (e.column() < 1 || static_cast<std::size_t>(e.column()) > size + 1) std::abort();
    return 0;
  }
  const std::string printed = to_text(bottle);
  if (to_text(parse_bottle(printed)) != printed) std::abort();
  try {
    (void)decode_skin_contact_list(bottle);
  } catch (const BottleSyntaxError&) {
  }
  return 0;
}
