// libFuzzer target: sweep-file YAML text through the sweep reader and the job expansion (keys,
// seeds, ranges, axes, repeated values, summary). Bad input must be an InputError; anything else
// escaping (or a sanitizer report, or a hang on a huge range) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "somasim/error.hpp"
#include "somasim/sweep/jobs.hpp"
#include "somasim/sweep/sweep_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // The experiment named by the sweep is read relative to the shipped configs.
    const somasim::sweep::SweepSpec spec = somasim::sweep::load_sweep_text(
        text, "<fuzz>", SOMASIM_FUZZ_ASSETS_DIR "/../configs/sweeps");
    (void)somasim::sweep::expand_jobs(spec);
  } catch (const somasim::InputError&) {
  }
  return 0;
}
