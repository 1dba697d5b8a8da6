// The particle study's compared filters: each size runs its own filter on the same likelihood
// (here a Gaussian around a known offset), their estimates come back in the order of the sizes
// and approach the offset, a new movement starts them afresh, and the metrics per size hold
// the recorded errors (null where none was recorded).
#include <gtest/gtest.h>

#include <vector>

#include "particle_comparison.hpp"

using somasim::plugins::particle_metrics;
using somasim::plugins::ParticleComparison;

namespace {

const Eigen::Vector2d kOffsetDeg(3.0, -2.0);

std::vector<double> likelihoods(const Eigen::MatrixXd& particles_deg) {
  std::vector<double> out;
  for (Eigen::Index i = 0; i < particles_deg.cols(); ++i)
    out.push_back(std::exp(-0.5 * (particles_deg.col(i) - kOffsetDeg).squaredNorm()));
  return out;
}

ParticleComparison comparison() {
  return ParticleComparison({50, 400}, 2, somasim::body_schema::noise_schedule_preset("paper"), {},
                            7, 2.0);
}

}  // namespace

TEST(ParticleComparison, EverySizeConvergesOnTheSameLikelihood) {
  ParticleComparison c = comparison();
  ASSERT_FALSE(c.empty());
  for (int frame = 0; frame < 40; ++frame) c.step(likelihoods);
  const auto estimates = c.estimates();
  ASSERT_EQ(estimates.size(), 2u);
  for (const Eigen::VectorXd& e : estimates) EXPECT_LT((e - kOffsetDeg).norm(), 0.5) << e;
  for (const auto& r : c.records()) EXPECT_EQ(r.step_ms.size(), 40u);
  EXPECT_EQ(c.records()[0].particles, 50);
  EXPECT_EQ(c.records()[1].particles, 400);
  c.reset();
  for (const Eigen::VectorXd& e : c.estimates()) EXPECT_EQ(e, Eigen::Vector2d::Zero());
}

TEST(ParticleComparison, MetricsPerSize) {
  ParticleComparison c = comparison();
  c.step(likelihoods);
  c.record_error(1, 4.0, 2.0);
  c.record_error(1, 6.0, 4.0);
  const nlohmann::json m = particle_metrics(c.records());
  EXPECT_DOUBLE_EQ(m["particles_400_estimation_error_mm"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(m["particles_400_estimation_error_deg_sd"].get<double>(), std::sqrt(2.0));
  EXPECT_TRUE(m["particles_400_step_ms"].is_number());
  EXPECT_TRUE(m["particles_50_estimation_error_mm"].is_null());
}

TEST(ParticleComparison, NoSizesIsEmpty) {
  const ParticleComparison c({}, 2, {}, {}, 1, 2.0);
  EXPECT_TRUE(c.empty());
  EXPECT_TRUE(c.estimates().empty());
}
