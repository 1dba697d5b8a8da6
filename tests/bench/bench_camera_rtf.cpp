// The `camera` node (both eyes, RGB + depth + id mask, textured backdrop, ~30 Hz; nothing reads
// its images, so it renders none) inside the 1 kHz ball_on_forearm world: real-time factor (sim
// time / wall time of the run loop, from the run's metrics.json) of
// configs/ball_on_forearm_camera.yaml beside, in the same iteration, configs/ball_on_forearm.yaml
// (the same world without the camera) as the baseline. Whole `somasim run` child processes; run
// folders under the system temp folder.
//
// Counters (means over iterations): rtf_without, rtf_with, slowdown = rtf_without / rtf_with,
// camera_frames (stereo frames rendered per run), sim_s (simulated seconds per run).
// The benchmark's time is the wall time of the run with the camera.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;

const std::string kConfigs = std::string(SOMASIM_SOURCE_DIR) + "/configs/";
const fs::path kOut = fs::temp_directory_path() / "somasim-bench-camera-rtf";

// Runs `config` into a fresh run folder and returns its metrics (null on failure).
nlohmann::json run(const std::string& config, const std::string& folder) {
  const fs::path out = kOut / folder;
  const std::string command = std::string(SOMASIM_BIN) + " run " + kConfigs + config +
                              " --quiet --overwrite --out " + out.string() + " > /dev/null";
  if (std::system(command.c_str()) != 0) return nullptr;
  std::ifstream in(out / "metrics.json");
  return nlohmann::json::parse(in, nullptr, false);
}

void BM_BallOnForearm_CameraVsNone(benchmark::State& state) {
  double without = 0.0, with = 0.0, frames = 0.0, sim_s = 0.0;
  for (auto _ : state) {
    const nlohmann::json base = run("ball_on_forearm.yaml", "without");
    const auto t0 = std::chrono::steady_clock::now();
    const nlohmann::json cam = run("ball_on_forearm_camera.yaml", "with");
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (base.is_discarded() || cam.is_discarded() || base.is_null() || cam.is_null() ||
        base.value("status", "") != "completed" || cam.value("status", "") != "completed") {
      const std::string error = "a run failed; see its log.txt under " + kOut.string();
      state.SkipWithError(error.c_str());
      return;
    }
    without += base.value("real_time_factor", 0.0);
    with += cam.value("real_time_factor", 0.0);
    frames += cam["nodes"]["cam"].value("frames", 0.0);
    sim_s += cam.value("sim_time_s", 0.0);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["rtf_without"] = without / n;
  state.counters["rtf_with"] = with / n;
  state.counters["slowdown"] = with > 0.0 ? without / with : 0.0;
  state.counters["camera_frames"] = frames / n;
  state.counters["sim_s"] = sim_s / n;
}

}  // namespace

BENCHMARK(BM_BallOnForearm_CameraVsNone)->Iterations(2)->Unit(benchmark::kSecond)->UseManualTime();
