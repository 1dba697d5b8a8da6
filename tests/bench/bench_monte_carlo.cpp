// The 500-throw single-taxel Monte Carlo (PPS paper Fig 3), whole process: `somasim run` as a
// child process, start-up, plugin loading, simulation, figures and outputs included.
// Baseline in the same run: `somasim validate` of the same file (process start-up, plugin
// loading and YAML validation only).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace {

const std::string kConfig =
    std::string(SOMASIM_SOURCE_DIR) + "/configs/pps_single_taxel_offset.yaml";
// Every repetition writes a whole run into this folder, emptied first (--overwrite).
const std::string kOut =
    (std::filesystem::temp_directory_path() / ("somasim-bench-mc-" + std::to_string(::getpid())))
        .string();

void run_command(benchmark::State& state, const std::string& command) {
  for (auto _ : state) {
    if (std::system(command.c_str()) != 0) {
      state.SkipWithError(("failed: " + command).c_str());
      break;
    }
  }
}

void BM_MonteCarlo500Throws_WholeProcess(benchmark::State& state) {
  run_command(state, std::string(SOMASIM_BIN) + " run " + kConfig + " --quiet --overwrite --out " +
                         kOut + " > /dev/null");
  std::filesystem::remove_all(kOut);
}

void BM_Baseline_ValidateOnly(benchmark::State& state) {
  run_command(state, std::string(SOMASIM_BIN) + " validate " + kConfig + " > /dev/null");
}

}  // namespace

BENCHMARK(BM_Baseline_ValidateOnly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_MonteCarlo500Throws_WholeProcess)->Unit(benchmark::kMillisecond)->UseRealTime();
