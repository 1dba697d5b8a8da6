#pragma once
/// @file
/// Schedules of the particle filter's noise (Vicente et al. 2016; ../shared/PAPERS.md B): the
/// spread of the initial particles σ_i and of the artificial dynamic noise σ_s added at every
/// prediction, and how σ_s evolves from frame to frame. All angles in degrees.
///
/// Presets:
/// - `paper` (text): σ_i = 5°, σ_s = 4° × 0.8 per frame, floor 0.08°, resample every frame.
/// - `code2016` (released code): σ_i = 3.5°, σ_s = 3°, × 0.85 after a resampling and × 1.15
///   otherwise, clamped to [0.04°, 3.5°]; resample only when the best likelihood exceeds 0.55.
/// - `code2017`: as code2016 with × 1.2 when not resampling, and particle 0 reset to β = 0 at
///   every prediction (the nominal model always stays a hypothesis).
#include <string>
#include <string_view>
#include <vector>

namespace somasim::body_schema {

struct NoiseSchedule {
  double initial_sigma_deg = 5.0;        ///< σ_i of the initial N(0, σ_i²) per joint [deg]
  double step_sigma_deg = 4.0;           ///< σ_s of the first prediction [deg]
  double factor_after_resample = 0.8;    ///< σ_s multiplier after a frame that resampled
  double factor_without_resample = 0.8;  ///< σ_s multiplier after a frame that did not
  double min_sigma_deg = 0.08;           ///< floor of σ_s [deg]
  double max_sigma_deg = 1.0e9;          ///< ceiling of σ_s [deg]
  /// Resample only when the best likelihood of the frame exceeds this (0: always resample).
  double resample_threshold = 0.0;
  bool reset_particle_zero = false;  ///< particle 0 is set to β = 0 at every prediction
  /// Mixture proposal against early lock-in (not in the paper; 0 = off, the presets' value):
  /// at every prediction each particle, with this probability, takes a jump of
  /// N(0, max(σ_s, jump_sigma_deg)²) instead of N(0, σ_s²). Once σ_s has decayed the population
  /// cannot leave a wrong mode by itself; the jumpers probe around it at no extra rendering cost,
  /// and resampling moves the population when one of them explains the images better.
  double jump_fraction = 0.0;
  double jump_sigma_deg = 0.0;  ///< σ of a jump [deg] (used when jump_fraction > 0)

  /// σ_s for the next frame, from this frame's σ_s and whether this frame resampled.
  double next_sigma(double sigma_deg, bool resampled) const;
};

/// The preset `name` (paper, code2016, code2017). Throws somasim::InputError
/// "unknown noise schedule 'X' (expected paper, code2016 or code2017)".
NoiseSchedule noise_schedule_preset(std::string_view name);
/// The preset names, in the order of the file comment.
const std::vector<std::string>& noise_schedule_names();

}  // namespace somasim::body_schema
