#pragma once
/// @file
/// The body-schema particle filter over joint offsets β (Vicente et al. 2016; PAPERS.md B):
/// M particles, each a vector of per-joint offsets [deg]. One frame = predict() (add the
/// artificial dynamic noise N(0, σ_s²)), the caller scores every particle (rendered hypotheses
/// against the camera images), update() (weights ∝ likelihoods, KDE-smoothed estimate,
/// systematic resampling, next σ_s). Every particle has weight 1/M at the start of a frame.
///
/// Determinism: every random draw comes from the filter's own std::mt19937_64 seeded by the
/// caller, in a fixed order, so the same seed and likelihoods give the same particles.
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "somasim/body_schema/noise_schedule.hpp"

namespace somasim::body_schema {

/// KDE smoothing of the estimate: ω'_i = ω_i + α (1/M) Σ_m ω_m K(β_i, β_m) with the Gaussian
/// kernel K = exp(−½ ‖β_i − β_m‖² / σ²) / |Σ|, Σ = σ² I (σ in degrees; paper: σ = 1°, α = 500).
///
/// Up to `exact_max_particles` particles every ω'_i is computed (O(M²) kernel evaluations).
/// Above it the candidates are screened first: the neighbour sum of every particle is estimated
/// from `screen_samples` particles drawn by weight (systematic, fixed offset: no random draw),
/// and ω' is computed exactly only for the `screen_keep` best screened particles and the
/// `screen_keep` heaviest ones: O(M (S + K)). The screened pick is the exact argmax whenever the
/// exact argmax is among those candidates, else a candidate of nearly the same score.
struct KdeOptions {
  double sigma_deg = 1.0;  ///< σ_KDE [deg]
  double alpha = 500.0;
  int exact_max_particles = 4096;  ///< largest M scored exhaustively (>= 1)
  int screen_samples = 512;        ///< S: draws by weight estimating each neighbour sum (>= 1)
  int screen_keep = 64;            ///< K: candidates of each kind scored exactly (>= 1)

  /// The options as configuration fields (somasim/config.hpp): kde_sigma_deg, kde_alpha,
  /// kde_exact_max_particles, kde_screen_samples, kde_screen_keep.
  template <class V>
  void visit(V& v) {
    v.field("kde_sigma_deg", sigma_deg).unit("deg").at_least(1e-9).doc("σ_KDE of the estimate");
    v.field("kde_alpha", alpha).at_least(0.0).doc("α of the estimate's KDE");
    v.field("kde_exact_max_particles", exact_max_particles)
        .at_least(1)
        .doc(
            "up to this M every particle's KDE score is computed (O(M²)); above it candidates are "
            "screened by kde_screen_samples draws and kde_screen_keep are scored exactly");
    v.field("kde_screen_samples", screen_samples)
        .at_least(1)
        .doc("particles drawn by weight to screen the KDE's candidates (M above the exact limit)");
    v.field("kde_screen_keep", screen_keep)
        .at_least(1)
        .doc("best screened and heaviest particles whose KDE score is computed exactly");
  }
};

/// What one update() saw and did.
struct FilterUpdate {
  double best_likelihood = 0.0;  ///< largest likelihood of the frame
  double mean_likelihood = 0.0;
  double effective_sample_size = 0.0;  ///< 1 / Σ w², w the normalised weights (1 ... M)
  bool resampled = false;
  double sigma_deg = 0.0;  ///< σ_s used by this frame's prediction
  int best_particle = 0;   ///< index (before resampling) of the particle chosen as the estimate
};

class OffsetParticleFilter {
 public:
  /// `dims` offsets (>= 1), `particles` M (>= 1). Throws somasim::InputError otherwise
  /// ("body schema filter: M must be >= 1, got 0"). Calls reset().
  OffsetParticleFilter(int dims, int particles, const NoiseSchedule& schedule, std::uint64_t seed,
                       const KdeOptions& kde = {});

  /// New movement: particles drawn from N(0, σ_i² I), σ_s back to its first value, estimate 0.
  void reset();
  /// Adds N(0, σ_s² I) to every particle (particle 0 set to 0 first under reset_particle_zero);
  /// a share `jump_fraction` of them, drawn at random, get N(0, max(σ_s, jump_sigma_deg)² I).
  void predict();
  /// Weights the particles by `likelihoods` (size M, finite, >= 0), picks the estimate, resamples
  /// (systematic) when the schedule says so and sets the next σ_s. A frame whose likelihoods are
  /// all 0 keeps the particles and the estimate, does not resample and returns best = 0: the
  /// caller decides (see the body_schema_filter plugin). Throws somasim::InputError for a wrong
  /// size or a negative or non-finite likelihood.
  FilterUpdate update(const std::vector<double>& likelihoods);

  const Eigen::MatrixXd& particles() const { return particles_; }  ///< dims × M [deg]
  /// Replaces the particles (dims × M [deg]); for tests and for ranks that receive them.
  void set_particles(const Eigen::MatrixXd& particles);
  const Eigen::VectorXd& estimate() const { return estimate_; }  ///< β̂ [deg]
  double sigma_deg() const { return sigma_; }                    ///< σ_s of the next predict()
  int size() const { return static_cast<int>(particles_.cols()); }
  int dims() const { return static_cast<int>(particles_.rows()); }
  const NoiseSchedule& schedule() const { return schedule_; }

  /// Multiplies σ_s by `factor`, up to the larger of σ_i and the first σ_s (never above the
  /// schedule's ceiling); used to re-inflate the noise after a frame in which no particle
  /// explained the images.
  void inflate_sigma(double factor);

  /// Threads for the estimate's KDE (kde_argmax; >= 1, default 1): the same estimate for any
  /// count. Throws somasim::InputError below 1.
  void set_estimate_threads(int threads);

 private:
  int kde_best(const Eigen::VectorXd& weights) const;
  void resample_systematic(const Eigen::VectorXd& weights);

  NoiseSchedule schedule_;
  KdeOptions kde_;
  std::uint64_t seed_;
  std::mt19937_64 rng_;
  Eigen::MatrixXd particles_;
  Eigen::VectorXd estimate_;
  double sigma_ = 0.0;
  int estimate_threads_ = 1;
};

/// The particle (column of `particles`, dims × M [deg]) with the largest KDE-smoothed weight
/// ω_i + α (1/M) Σ_m ω_m K(β_i, β_m) (KdeOptions; the lowest index wins ties): O(M²) kernel
/// evaluations up to kde.exact_max_particles, screened candidates above (see KdeOptions;
/// bench_body_schema's BM_KdeArgmax measures both up to M = 10⁴). `weights` sum to 1. `threads`
/// (>= 1) share the candidates in contiguous ranges, each score computed exactly as with one
/// thread, so the index is the same for any count; fewer threads run where M is small (at least
/// 256 candidates each).
int kde_argmax(const Eigen::MatrixXd& particles, const Eigen::VectorXd& weights,
               const KdeOptions& kde, int threads = 1);

/// The KDE-smoothed weight ω_i + α (1/M) Σ_m ω_m K(β_i, β_m) of particle `i` (column of
/// `particles`, dims × M [deg]; `weights` sum to 1): the score kde_argmax maximises.
double kde_score(const Eigen::MatrixXd& particles, const Eigen::VectorXd& weights,
                 const KdeOptions& kde, int i);

/// Indices chosen by systematic resampling of normalised `weights` (sum 1) with the offset
/// u0 in [0, 1/M): particle i is copied floor or ceil of M·w_i times, in index order.
std::vector<int> systematic_resample(const Eigen::VectorXd& weights, double u0);

}  // namespace somasim::body_schema
