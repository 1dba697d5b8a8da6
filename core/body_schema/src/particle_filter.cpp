#include "somasim/body_schema/particle_filter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include "somasim/error.hpp"

namespace somasim::body_schema {

OffsetParticleFilter::OffsetParticleFilter(int dims, int particles, const NoiseSchedule& schedule,
                                           std::uint64_t seed, const KdeOptions& kde)
    : schedule_(schedule), kde_(kde), seed_(seed), rng_(seed) {
  if (dims < 1)
    throw InputError(fmt::format("body schema filter: need at least one offset, got {}", dims));
  if (particles < 1)
    throw InputError(fmt::format("body schema filter: M must be >= 1, got {}", particles));
  if (!(kde.sigma_deg > 0.0) || !(kde.alpha >= 0.0))
    throw InputError(
        fmt::format("body schema filter: KDE sigma must be > 0 and alpha >= 0, got {} and {}",
                    kde.sigma_deg, kde.alpha));
  particles_.resize(dims, particles);
  reset();
}

void OffsetParticleFilter::reset() {
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (Eigen::Index m = 0; m < particles_.cols(); ++m)
    for (Eigen::Index j = 0; j < particles_.rows(); ++j)
      particles_(j, m) = schedule_.initial_sigma_deg * gauss(rng_);
  estimate_ = Eigen::VectorXd::Zero(particles_.rows());
  sigma_ = schedule_.step_sigma_deg;
}

void OffsetParticleFilter::predict() {
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const bool jumps = schedule_.jump_fraction > 0.0;  // no extra draws when off: same stream
  const double jump_sigma = std::max(sigma_, schedule_.jump_sigma_deg);
  if (schedule_.reset_particle_zero) particles_.col(0).setZero();
  for (Eigen::Index m = 0; m < particles_.cols(); ++m) {
    const bool keep = schedule_.reset_particle_zero && m == 0;
    const bool jump = jumps && uniform(rng_) < schedule_.jump_fraction;
    const double sigma = jump ? jump_sigma : sigma_;
    for (Eigen::Index j = 0; j < particles_.rows(); ++j) {
      const double w = sigma * gauss(rng_);  // drawn for particle 0 too: same stream either way
      if (!keep) particles_(j, m) += w;
    }
  }
}

void OffsetParticleFilter::set_particles(const Eigen::MatrixXd& particles) {
  if (particles.rows() != particles_.rows() || particles.cols() != particles_.cols())
    throw InputError(fmt::format("body schema filter: particles must be {} x {}, got {} x {}",
                                 particles_.rows(), particles_.cols(), particles.rows(),
                                 particles.cols()));
  particles_ = particles;
}

void OffsetParticleFilter::inflate_sigma(double factor) {
  const double ceiling = std::min(schedule_.max_sigma_deg,
                                  std::max(schedule_.initial_sigma_deg, schedule_.step_sigma_deg));
  sigma_ = std::clamp(sigma_ * factor, schedule_.min_sigma_deg, std::max(ceiling, sigma_));
}

FilterUpdate OffsetParticleFilter::update(const std::vector<double>& likelihoods) {
  const auto m_count = static_cast<std::size_t>(particles_.cols());
  if (likelihoods.size() != m_count)
    throw InputError(fmt::format("body schema filter: expected {} likelihoods, got {}", m_count,
                                 likelihoods.size()));
  FilterUpdate out;
  out.sigma_deg = sigma_;
  double sum = 0.0;
  for (std::size_t m = 0; m < m_count; ++m) {
    const double l = likelihoods[m];
    if (!std::isfinite(l) || l < 0.0)
      throw InputError(fmt::format(
          "body schema filter: likelihood of particle {} is {} (expected finite and >= 0)", m, l));
    sum += l;
    out.best_likelihood = std::max(out.best_likelihood, l);
  }
  out.mean_likelihood = sum / static_cast<double>(m_count);
  if (!(sum > 0.0)) return out;  // nothing explains the images: the caller decides

  Eigen::VectorXd weights(static_cast<Eigen::Index>(m_count));
  for (std::size_t m = 0; m < m_count; ++m)
    weights[static_cast<Eigen::Index>(m)] = likelihoods[m] / sum;
  out.effective_sample_size = 1.0 / weights.squaredNorm();
  out.best_particle = kde_best(weights);
  estimate_ = particles_.col(out.best_particle);

  out.resampled = out.best_likelihood > schedule_.resample_threshold;
  if (out.resampled) resample_systematic(weights);
  sigma_ = schedule_.next_sigma(sigma_, out.resampled);
  return out;
}

int OffsetParticleFilter::kde_best(const Eigen::VectorXd& weights) const {
  return kde_argmax(particles_, weights, kde_, estimate_threads_);
}

void OffsetParticleFilter::set_estimate_threads(int threads) {
  if (threads < 1)
    throw InputError(
        fmt::format("body schema filter: estimate threads must be >= 1, got {}", threads));
  estimate_threads_ = threads;
}

void OffsetParticleFilter::resample_systematic(const Eigen::VectorXd& weights) {
  const double step = 1.0 / static_cast<double>(particles_.cols());
  std::uniform_real_distribution<double> uniform(0.0, step);
  const std::vector<int> chosen = systematic_resample(weights, uniform(rng_));
  Eigen::MatrixXd next(particles_.rows(), particles_.cols());
  for (std::size_t m = 0; m < chosen.size(); ++m)
    next.col(static_cast<Eigen::Index>(m)) = particles_.col(chosen[m]);
  particles_.swap(next);
}

std::vector<int> systematic_resample(const Eigen::VectorXd& weights, double u0) {
  const auto m_count = static_cast<int>(weights.size());
  const double step = 1.0 / static_cast<double>(m_count);
  std::vector<int> chosen(static_cast<std::size_t>(m_count));
  double cumulative = weights[0];
  int i = 0;
  for (int m = 0; m < m_count; ++m) {
    const double u = u0 + step * static_cast<double>(m);
    while (u >= cumulative && i < m_count - 1) cumulative += weights[++i];
    chosen[static_cast<std::size_t>(m)] = i;
  }
  return chosen;
}

namespace {

struct Candidate {
  double score = -1.0;
  int index = 0;
};

// The best of the candidates [first, last): strict comparison, so the lowest index wins ties.
Candidate kde_best_in(const Eigen::MatrixXd& particles, const Eigen::VectorXd& weights,
                      const KdeOptions& kde, Eigen::Index first, Eigen::Index last) {
  const Eigen::Index m_count = particles.cols();
  const double inv_two_var = 0.5 / (kde.sigma_deg * kde.sigma_deg);
  // |Σ| = σ^(2 dims) for Σ = σ² I.
  const double norm = std::pow(kde.sigma_deg, -2.0 * static_cast<double>(particles.rows()));
  const double scale = kde.alpha * norm / static_cast<double>(m_count);
  Candidate best;
  for (Eigen::Index i = first; i < last; ++i) {
    double neighbours = 0.0;
    for (Eigen::Index m = 0; m < m_count; ++m) {
      if (weights[m] == 0.0) continue;
      const double d2 = (particles.col(i) - particles.col(m)).squaredNorm();
      neighbours += weights[m] * std::exp(-d2 * inv_two_var);
    }
    const double score = weights[i] + scale * neighbours;
    if (score > best.score) best = {score, static_cast<int>(i)};
  }
  return best;
}

}  // namespace

int kde_argmax(const Eigen::MatrixXd& particles, const Eigen::VectorXd& weights,
               const KdeOptions& kde, int threads) {
  constexpr Eigen::Index kLeastPerThread = 256;
  const Eigen::Index m_count = particles.cols();
  const auto parts = static_cast<Eigen::Index>(
      std::clamp<Eigen::Index>(m_count / kLeastPerThread, 1, std::max(threads, 1)));
  if (parts == 1) return kde_best_in(particles, weights, kde, 0, m_count).index;
  std::vector<Candidate> best(static_cast<std::size_t>(parts));
  auto range = [&](Eigen::Index part) { return part * m_count / parts; };
  {
    std::vector<std::jthread> workers;
    for (Eigen::Index part = 1; part < parts; ++part)
      workers.emplace_back([&, part] {
        best[static_cast<std::size_t>(part)] =
            kde_best_in(particles, weights, kde, range(part), range(part + 1));
      });
    best[0] = kde_best_in(particles, weights, kde, 0, range(1));
  }
  // Ranges in index order, strict comparison: the lowest index wins ties, as with one thread.
  Candidate winner = best[0];
  for (const Candidate& c : best)
    if (c.score > winner.score) winner = c;
  return winner.index;
}

}  // namespace somasim::body_schema
