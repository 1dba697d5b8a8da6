#include "somasim/body_schema/particle_filter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <thread>
#include <utility>
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
  if (kde.exact_max_particles < 1 || kde.screen_samples < 1 || kde.screen_keep < 1)
    throw InputError(fmt::format(
        "body schema filter: KDE exact limit, screen samples and screen keep must be >= 1, got "
        "{}, {} and {}",
        kde.exact_max_particles, kde.screen_samples, kde.screen_keep));
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

// The kernel's constants: score_i = ω_i + scale Σ_m ω_m exp(−d²_im · inv_two_var).
struct KdeKernel {
  double inv_two_var = 0.0;
  double scale = 0.0;

  KdeKernel(const KdeOptions& kde, Eigen::Index dims, Eigen::Index m_count)
      : inv_two_var(0.5 / (kde.sigma_deg * kde.sigma_deg)),
        // |Σ| = σ^(2 dims) for Σ = σ² I.
        scale(kde.alpha * std::pow(kde.sigma_deg, -2.0 * static_cast<double>(dims)) /
              static_cast<double>(m_count)) {}
};

double exact_score(const Eigen::MatrixXd& particles, const Eigen::VectorXd& weights,
                   const KdeKernel& kernel, Eigen::Index i) {
  double neighbours = 0.0;
  for (Eigen::Index m = 0; m < particles.cols(); ++m) {
    if (weights[m] == 0.0) continue;
    const double d2 = (particles.col(i) - particles.col(m)).squaredNorm();
    neighbours += weights[m] * std::exp(-d2 * kernel.inv_two_var);
  }
  return weights[i] + kernel.scale * neighbours;
}

// Runs body(first, last) over [0, count) split into contiguous ranges, one per thread (at least
// 256 items each), and returns the ranges' results in index order.
template <class Body>
auto over_ranges(Eigen::Index count, int threads, Body body) {
  constexpr Eigen::Index kLeastPerThread = 256;
  const auto parts = static_cast<Eigen::Index>(
      std::clamp<Eigen::Index>(count / kLeastPerThread, 1, std::max(threads, 1)));
  std::vector<decltype(body(Eigen::Index{0}, Eigen::Index{0}))> results(
      static_cast<std::size_t>(parts));
  auto range = [&](Eigen::Index part) { return part * count / parts; };
  {
    std::vector<std::jthread> workers;
    for (Eigen::Index part = 1; part < parts; ++part)
      workers.emplace_back([&, part] {
        results[static_cast<std::size_t>(part)] = body(range(part), range(part + 1));
      });
    results[0] = body(0, range(1));
  }
  return results;
}

// The best of candidates[first, last) (ascending indices): strict comparison, so the lowest
// index wins ties.
Candidate best_of(const Eigen::MatrixXd& particles, const Eigen::VectorXd& weights,
                  const KdeKernel& kernel, const std::vector<Eigen::Index>& candidates,
                  int threads) {
  const std::vector<Candidate> best =
      over_ranges(static_cast<Eigen::Index>(candidates.size()), threads,
                  [&](Eigen::Index first, Eigen::Index last) {
                    Candidate b;
                    for (Eigen::Index k = first; k < last; ++k) {
                      const Eigen::Index i = candidates[static_cast<std::size_t>(k)];
                      const double score = exact_score(particles, weights, kernel, i);
                      if (score > b.score) b = {score, static_cast<int>(i)};
                    }
                    return b;
                  });
  // Ranges in index order, strict comparison: the lowest index wins ties, as with one thread.
  Candidate winner = best[0];
  for (const Candidate& c : best)
    if (c.score > winner.score) winner = c;
  return winner;
}

// Particles drawn by weight, systematically with the offset 1/(2S), as (index, copies).
std::vector<std::pair<Eigen::Index, int>> screen_sample(const Eigen::VectorXd& weights,
                                                        int samples) {
  const Eigen::Index m_count = weights.size();
  const double total = weights.sum();
  const double step = total / static_cast<double>(samples);
  std::vector<std::pair<Eigen::Index, int>> drawn;
  double cumulative = weights[0];
  Eigen::Index i = 0;
  for (int s = 0; s < samples; ++s) {
    const double u = step * (static_cast<double>(s) + 0.5);
    while (u >= cumulative && i < m_count - 1) cumulative += weights[++i];
    if (!drawn.empty() && drawn.back().first == i)
      ++drawn.back().second;
    else
      drawn.emplace_back(i, 1);
  }
  return drawn;
}

// The indices of the `keep` largest values (ties: lower index first), in ascending index order.
std::vector<Eigen::Index> largest(const std::vector<double>& values, int keep) {
  std::vector<Eigen::Index> order(values.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<Eigen::Index>(k);
  const auto n = std::min<std::size_t>(order.size(), static_cast<std::size_t>(keep));
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n), order.end(),
                    [&](Eigen::Index a, Eigen::Index b) {
                      const double va = values[static_cast<std::size_t>(a)];
                      const double vb = values[static_cast<std::size_t>(b)];
                      return va > vb || (va == vb && a < b);
                    });
  order.resize(n);
  std::sort(order.begin(), order.end());
  return order;
}

// Candidates for exact scoring: the best by a neighbour sum estimated from the screen sample,
// and the heaviest particles.
std::vector<Eigen::Index> screened_candidates(const Eigen::MatrixXd& particles,
                                              const Eigen::VectorXd& weights, const KdeOptions& kde,
                                              const KdeKernel& kernel, int threads) {
  const Eigen::Index m_count = particles.cols();
  const auto drawn = screen_sample(weights, kde.screen_samples);
  const double per_draw = weights.sum() / static_cast<double>(kde.screen_samples);
  const auto parts = over_ranges(m_count, threads, [&](Eigen::Index first, Eigen::Index last) {
    std::vector<double> scores;
    scores.reserve(static_cast<std::size_t>(last - first));
    for (Eigen::Index i = first; i < last; ++i) {
      double neighbours = 0.0;
      for (const auto& [m, copies] : drawn) {
        const double d2 = (particles.col(i) - particles.col(m)).squaredNorm();
        neighbours += static_cast<double>(copies) * std::exp(-d2 * kernel.inv_two_var);
      }
      scores.push_back(weights[i] + kernel.scale * per_draw * neighbours);
    }
    return scores;
  });
  std::vector<double> screened;
  screened.reserve(static_cast<std::size_t>(m_count));
  for (const auto& part : parts) screened.insert(screened.end(), part.begin(), part.end());
  std::vector<Eigen::Index> candidates = largest(screened, kde.screen_keep);
  const std::vector<Eigen::Index> heaviest =
      largest(std::vector<double>(weights.data(), weights.data() + m_count), kde.screen_keep);
  std::vector<Eigen::Index> merged;
  std::set_union(candidates.begin(), candidates.end(), heaviest.begin(), heaviest.end(),
                 std::back_inserter(merged));
  return merged;
}

}  // namespace

double kde_score(const Eigen::MatrixXd& particles, const Eigen::VectorXd& weights,
                 const KdeOptions& kde, int i) {
  return exact_score(particles, weights, KdeKernel(kde, particles.rows(), particles.cols()), i);
}

int kde_argmax(const Eigen::MatrixXd& particles, const Eigen::VectorXd& weights,
               const KdeOptions& kde, int threads) {
  const Eigen::Index m_count = particles.cols();
  const KdeKernel kernel(kde, particles.rows(), m_count);
  std::vector<Eigen::Index> candidates;
  if (m_count <= kde.exact_max_particles) {
    candidates.resize(static_cast<std::size_t>(m_count));
    for (Eigen::Index i = 0; i < m_count; ++i) candidates[static_cast<std::size_t>(i)] = i;
  } else {
    candidates = screened_candidates(particles, weights, kde, kernel, threads);
  }
  return best_of(particles, weights, kernel, candidates, threads).index;
}

}  // namespace somasim::body_schema
