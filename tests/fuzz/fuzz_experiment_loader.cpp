// libFuzzer target: experiment YAML text through the whole loader (syntax, schema, plugin
// parameters against the test plugins, wiring). Bad input must be an InputError;
// anything else escaping (or a sanitizer report) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "somasim/error.hpp"
#include "somasim/experiment.hpp"
#include "somasim/plugin_registry.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // One registry for the whole run: plugins are loaded once, as in one somasim process.
  static somasim::PluginRegistry registry({SOMASIM_FUZZ_PLUGIN_DIR});
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)somasim::load_experiment_text(text, "<fuzz>", SOMASIM_FUZZ_ASSETS_DIR "/../configs",
                                        registry);
  } catch (const somasim::InputError&) {
  }
  return 0;
}
