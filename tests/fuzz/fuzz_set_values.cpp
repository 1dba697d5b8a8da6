// libFuzzer target: `--set PATH=VALUE` overrides on a valid experiment. The input is split at
// the first '=' (or used as the value of a counter parameter when it holds none) and applied
// through the loader as the command line does. Bad input must be an InputError; anything else
// escaping (or a sanitizer report) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "somasim/error.hpp"
#include "somasim/experiment.hpp"
#include "somasim/plugin_registry.hpp"

namespace {

const char* const kExperiment = R"(experiment: fuzz_set
seed: 1
duration_s: 1
nodes:
  c: {plugin: counter, params: {start: 0, increment: 1}}
  s: {plugin: adder, inputs: {a: c.value}}
record: [c.value]
)";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static somasim::PluginRegistry registry({SOMASIM_FUZZ_PLUGIN_DIR});
  const std::string text(reinterpret_cast<const char*>(data), size);
  somasim::LoadOptions options;
  const auto eq = text.find('=');
  if (eq == std::string::npos)
    options.overrides = {{"nodes.c.params.increment", text}};
  else
    options.overrides = {{text.substr(0, eq), text.substr(eq + 1)}};
  try {
    (void)somasim::load_experiment_text(kExperiment, "<fuzz>", "/nonexistent", registry, options);
  } catch (const somasim::InputError&) {
  }
  return 0;
}
