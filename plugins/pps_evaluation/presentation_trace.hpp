#pragma once
// Time series of one presentation for a Fig 10/11-style figure: per-taxel true distance and
// activation of the aimed part, and the speed its controller commanded.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "presentation_record.hpp"

namespace somasim::plugins {

struct PresentationTrace {
  std::uint64_t id = 0;
  std::vector<int> taxel_ids;  ///< the aimed part's taxels
  std::vector<double> time_s;  ///< sample times [s]
  /// Per sample, one value per taxel (taxel-major within a sample): distance [m] (NaN while the
  /// object is not in the world) and activation.
  std::vector<float> distance_m, activation;
  std::vector<double> controller_speed;  ///< [m/s] per sample; NaN when no controller is wired

  void add_sample(double t, const std::vector<double>& distances,
                  const std::vector<double>& activations, double speed);
};

/// Draws stacked panels (distance [cm] and activation of the `taxels` most activated taxels,
/// the threshold, the controller's speed) with the first trigger and first skin contact marked,
/// and writes them to `file`. InputError if the file cannot be written.
void draw_presentation_figure(const PresentationTrace& trace, const PresentationRecord& record,
                              double threshold, int taxels, const std::filesystem::path& file);

}  // namespace somasim::plugins
