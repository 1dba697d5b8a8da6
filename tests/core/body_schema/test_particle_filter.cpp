// The offset particle filter: systematic resampling, KDE estimate, convergence on a synthetic
// likelihood for every schedule preset, determinism and its errors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "somasim/body_schema/particle_filter.hpp"
#include "somasim/error.hpp"

namespace somasim::body_schema {
namespace {

const Eigen::Matrix<double, 7, 1> kTrueOffsets =
    (Eigen::Matrix<double, 7, 1>() << 5, 4, 3, -2, 3, -7, 3).finished();

// A smooth, unimodal stand-in for the image likelihood: 1 at the true offsets.
std::vector<double> synthetic_likelihoods(const OffsetParticleFilter& f, double width_deg) {
  std::vector<double> l(static_cast<std::size_t>(f.size()));
  for (int m = 0; m < f.size(); ++m) {
    const double d2 = (f.particles().col(m) - kTrueOffsets).squaredNorm();
    l[static_cast<std::size_t>(m)] = std::exp(-0.5 * d2 / (width_deg * width_deg));
  }
  return l;
}

// The code presets resample only when the best likelihood exceeds 0.55 and otherwise let the
// noise grow: they need a likelihood wide enough (8 deg here) that some initial particle passes.
Eigen::VectorXd run(const std::string& preset, int particles, int frames, std::uint64_t seed,
                    double width_deg) {
  OffsetParticleFilter f(7, particles, noise_schedule_preset(preset), seed);
  for (int t = 0; t < frames; ++t) {
    f.predict();
    f.update(synthetic_likelihoods(f, width_deg));
  }
  return f.estimate();
}

TEST(SystematicResample, CopiesParticlesInProportionToTheirWeights) {
  Eigen::VectorXd w(4);
  w << 0.5, 0.25, 0.25, 0.0;
  EXPECT_EQ(systematic_resample(w, 0.1), (std::vector<int>{0, 0, 1, 2}));
  EXPECT_EQ(systematic_resample(w, 0.0), (std::vector<int>{0, 0, 1, 2}));
  EXPECT_EQ(systematic_resample(w, 0.2499), (std::vector<int>{0, 0, 1, 2}));
  Eigen::VectorXd one = Eigen::VectorXd::Zero(5);
  one[3] = 1.0;
  EXPECT_EQ(systematic_resample(one, 0.19), (std::vector<int>(5, 3)));
}

TEST(OffsetParticleFilter, ConvergesToTheTrueOffsetsWithEveryPreset) {
  for (const std::string& preset : noise_schedule_names()) {
    for (std::uint64_t seed : {1U, 2U, 3U}) {
      const Eigen::VectorXd estimate = run(preset, 200, 80, seed, preset == "paper" ? 3.0 : 8.0);
      // The wider likelihood of the code presets leaves a wider posterior.
      EXPECT_LT((estimate - kTrueOffsets).cwiseAbs().maxCoeff(), preset == "paper" ? 1.5 : 2.5)
          << preset << " seed " << seed << ": " << estimate.transpose();
    }
  }
}

TEST(OffsetParticleFilter, EstimateIsZeroBeforeTheFirstUpdateAndAfterReset) {
  OffsetParticleFilter f(7, 50, noise_schedule_preset("paper"), 4);
  EXPECT_EQ(f.estimate(), Eigen::VectorXd::Zero(7));
  f.predict();
  f.update(synthetic_likelihoods(f, 3.0));
  EXPECT_NE(f.estimate(), Eigen::VectorXd::Zero(7));
  f.reset();
  EXPECT_EQ(f.estimate(), Eigen::VectorXd::Zero(7));
  EXPECT_DOUBLE_EQ(f.sigma_deg(), 4.0);
}

TEST(OffsetParticleFilter, SameSeedSameParticlesOtherSeedOtherParticles) {
  EXPECT_EQ(run("paper", 100, 10, 7, 3.0), run("paper", 100, 10, 7, 3.0));
  EXPECT_NE(run("paper", 100, 10, 7, 3.0), run("paper", 100, 10, 8, 3.0));
}

TEST(OffsetParticleFilter, KdePrefersAClusterToAnIsolatedHeavierParticle) {
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(2, 6);
  p.col(0) << 10.0, 10.0;  // isolated
  for (int m = 1; m < 6; ++m) p.col(m) << 0.1 * m, 0.0;
  const std::vector<double> l = {0.3, 0.14, 0.14, 0.14, 0.14, 0.14};
  for (double alpha : {0.0, 500.0}) {
    OffsetParticleFilter f(2, 6, noise_schedule_preset("paper"), 1, KdeOptions{1.0, alpha});
    f.set_particles(p);
    const FilterUpdate u = f.update(l);
    if (alpha == 0.0) {
      EXPECT_EQ(u.best_particle, 0);
    } else {
      EXPECT_GE(u.best_particle, 1);
      EXPECT_LE(u.best_particle, 5);
    }
  }
}

TEST(OffsetParticleFilter, Code2016ResamplesOnlyAboveTheThreshold) {
  OffsetParticleFilter f(7, 10, noise_schedule_preset("code2016"), 1);
  const Eigen::MatrixXd before = f.particles();
  FilterUpdate u = f.update(std::vector<double>(10, 0.5));
  EXPECT_FALSE(u.resampled);
  EXPECT_EQ(f.particles(), before);
  EXPECT_DOUBLE_EQ(f.sigma_deg(), 3.45);
  std::vector<double> l(10, 0.01);
  l[4] = 0.9;
  u = f.update(l);
  EXPECT_TRUE(u.resampled);
  EXPECT_DOUBLE_EQ(u.sigma_deg, 3.45);
  EXPECT_NEAR(f.sigma_deg(), 3.45 * 0.85, 1e-12);
  EXPECT_EQ(u.best_particle, 4);
  EXPECT_NEAR(u.effective_sample_size, 1.0 / ((0.9 * 0.9 + 9e-4) / (0.99 * 0.99)), 1e-9);
}

TEST(OffsetParticleFilter, Code2017KeepsParticleZeroAtTheNominalModel) {
  OffsetParticleFilter f(7, 20, noise_schedule_preset("code2017"), 3);
  f.predict();
  EXPECT_EQ(Eigen::VectorXd(f.particles().col(0)), Eigen::VectorXd::Zero(7));
  EXPECT_NE(Eigen::VectorXd(f.particles().col(1)), Eigen::VectorXd::Zero(7));
}

TEST(OffsetParticleFilter, AllZeroLikelihoodsChangeNothing) {
  OffsetParticleFilter f(7, 20, noise_schedule_preset("paper"), 3);
  f.predict();
  const Eigen::MatrixXd before = f.particles();
  const FilterUpdate u = f.update(std::vector<double>(20, 0.0));
  EXPECT_EQ(u.best_likelihood, 0.0);
  EXPECT_FALSE(u.resampled);
  EXPECT_EQ(f.particles(), before);
  EXPECT_EQ(f.estimate(), Eigen::VectorXd::Zero(7));
  EXPECT_DOUBLE_EQ(f.sigma_deg(), 4.0);
  f.inflate_sigma(1.2);
  EXPECT_DOUBLE_EQ(f.sigma_deg(), 4.8);
  f.inflate_sigma(2.0);
  EXPECT_DOUBLE_EQ(f.sigma_deg(), 5.0);  // up to σ_i, not beyond
}

TEST(OffsetParticleFilter, JumpsMoveTheirShareOfParticlesWithTheirOwnSigma) {
  NoiseSchedule s = noise_schedule_preset("paper");
  s.step_sigma_deg = 0.01;
  s.jump_fraction = 0.2;
  s.jump_sigma_deg = 2.0;
  constexpr int kParticles = 2000;
  OffsetParticleFilter f(7, kParticles, s, 5);
  f.set_particles(Eigen::MatrixXd::Zero(7, kParticles));
  f.predict();
  int jumped = 0;
  double jump_sq = 0.0;
  for (int m = 0; m < kParticles; ++m) {
    const double n = f.particles().col(m).norm();
    EXPECT_TRUE(n < 0.1 || n > 0.3) << n;  // 7-D norms: ~0.026 for σ_s, ~5.3 for a jump
    if (n > 0.3) {
      ++jumped;
      jump_sq += n * n;
    }
  }
  EXPECT_NEAR(jumped, 0.2 * kParticles, 4.0 * std::sqrt(kParticles * 0.2 * 0.8));
  EXPECT_NEAR(std::sqrt(jump_sq / (7.0 * jumped)), 2.0, 0.1);  // per-joint σ of the jumps
}

// Two modes 6 deg apart: a broad one (peak 0.5) around the nominal model and a narrow, better
// one. The paper's decay freezes most populations in the broad mode; jumps find the better one.
TEST(OffsetParticleFilter, JumpsLeaveAWrongModeThePaperScheduleLocksOnto) {
  const Eigen::Vector2d wrong(0.0, 0.0);
  const Eigen::Vector2d right(6.0, 0.0);
  auto likelihoods = [&](const OffsetParticleFilter& f) {
    std::vector<double> l(static_cast<std::size_t>(f.size()));
    for (int m = 0; m < f.size(); ++m) {
      const Eigen::Vector2d b = f.particles().col(m);
      l[static_cast<std::size_t>(m)] = 0.5 * std::exp(-0.5 * (b - wrong).squaredNorm() / 9.0) +
                                       std::exp(-0.5 * (b - right).squaredNorm() / 0.25);
    }
    return l;
  };
  auto found = [&](double jump_fraction, std::uint64_t seed) {
    NoiseSchedule s = noise_schedule_preset("paper");
    s.initial_sigma_deg = 2.0;
    s.jump_fraction = jump_fraction;
    s.jump_sigma_deg = 3.0;
    OffsetParticleFilter f(2, 100, s, seed);
    for (int t = 0; t < 120; ++t) {
      f.predict();
      f.update(likelihoods(f));
    }
    return (f.estimate() - right).norm() < 1.0;
  };
  int paper_found = 0;
  int jumps_found = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    paper_found += found(0.0, seed) ? 1 : 0;
    jumps_found += found(0.1, seed) ? 1 : 0;
  }
  EXPECT_LE(paper_found, 6);
  EXPECT_GE(jumps_found, 18);
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// Generated clouds (resampled copies: exact ties; zero weights; flat and peaked weights, wide and
// narrow kernels): any thread count picks the index one thread picks.
TEST(KdeArgmax, AnyThreadCountPicksTheSameParticle) {
  std::mt19937 rng(17);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int cases = 0;
  for (const int m : {200, 513, 1024, 1777}) {
    for (int cloud = 0; cloud < 4; ++cloud) {
      const double spread = cloud % 2 == 0 ? 0.5 : 3.0;
      Eigen::MatrixXd p(7, m);
      for (int i = 0; i < m; ++i) {
        // One particle in three repeats an earlier one (as after resampling).
        if (i > 0 && i % 3 == 0) {
          p.col(i) = p.col(static_cast<Eigen::Index>(unit(rng) * i));
          continue;
        }
        for (int d = 0; d < 7; ++d) p(d, i) = spread * normal(rng);
      }
      Eigen::VectorXd w(m);
      for (int i = 0; i < m; ++i)
        w[i] = cloud < 2 ? 1.0 : std::pow(unit(rng), 6.0) * (unit(rng) < 0.2 ? 0.0 : 1.0);
      w /= w.sum();
      KdeOptions kde;
      kde.sigma_deg = cloud == 3 ? 0.3 : 1.0;
      const int serial = kde_argmax(p, w, kde, 1);
      for (const int threads : {2, 3, 4, 7})
        EXPECT_EQ(kde_argmax(p, w, kde, threads), serial)
            << "M " << m << ", cloud " << cloud << ", " << threads << " threads";
      ++cases;
    }
  }
  EXPECT_EQ(cases, 16);
  OffsetParticleFilter f(7, 3, noise_schedule_preset("paper"), 1);
  EXPECT_EQ(error_of([&] { f.set_estimate_threads(0); }),
            "body schema filter: estimate threads must be >= 1, got 0");
}

// Above the exhaustive limit the candidates are screened. On the clouds a filter produces (paper
// schedule, likelihoods of two widths, three seeds, every frame of a movement) the screened pick
// is the exhaustive one; a filter using screening converges as the exhaustive one does.
TEST(KdeArgmax, ScreeningPicksTheExhaustiveArgmaxOnAFiltersClouds) {
  constexpr int kParticles = 1200;
  KdeOptions exhaustive;
  exhaustive.exact_max_particles = kParticles;
  KdeOptions screened = exhaustive;
  screened.exact_max_particles = kParticles / 4;
  int frames = 0;
  int agree = 0;
  for (const double width : {1.0, 3.0}) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      OffsetParticleFilter f(7, kParticles, noise_schedule_preset("paper"), seed, screened);
      OffsetParticleFilter reference(7, kParticles, noise_schedule_preset("paper"), seed,
                                     exhaustive);
      for (int t = 0; t < 20; ++t) {
        f.predict();
        reference.predict();
        const std::vector<double> l = synthetic_likelihoods(f, width);
        Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(l.data(), kParticles);
        w /= w.sum();
        const int pick = kde_argmax(f.particles(), w, screened, 2);
        agree += pick == kde_argmax(f.particles(), w, exhaustive, 2) ? 1 : 0;
        ++frames;
        EXPECT_EQ(f.update(l).best_particle, pick);
        reference.update(synthetic_likelihoods(reference, width));
      }
      EXPECT_NEAR((f.estimate() - kTrueOffsets).norm(),
                  (reference.estimate() - kTrueOffsets).norm(), 0.25 * width)
          << "width " << width << ", seed " << seed;
    }
  }
  EXPECT_EQ(frames, 120);
  EXPECT_GE(agree, 117) << "of " << frames << " frames";
}

// The screen is the same for any thread count, and with every particle kept it is exhaustive.
TEST(KdeArgmax, ScreeningIsDeterministicAndExhaustiveWhenEveryParticleIsKept) {
  std::mt19937 rng(29);
  std::normal_distribution<double> normal(0.0, 2.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int cloud = 0; cloud < 6; ++cloud) {
    const int m = 600 + 97 * cloud;
    Eigen::MatrixXd p(7, m);
    for (Eigen::Index k = 0; k < p.size(); ++k) p.data()[k] = normal(rng);
    Eigen::VectorXd w(m);
    for (int i = 0; i < m; ++i) w[i] = cloud % 2 == 0 ? unit(rng) : std::pow(unit(rng), 8.0);
    w /= w.sum();
    KdeOptions screened;
    screened.exact_max_particles = 100;
    screened.screen_samples = 64;
    const int serial = kde_argmax(p, w, screened, 1);
    for (const int threads : {2, 3}) EXPECT_EQ(kde_argmax(p, w, screened, threads), serial);
    KdeOptions all = screened;
    all.screen_keep = m;
    EXPECT_EQ(kde_argmax(p, w, all, 2), kde_argmax(p, w, KdeOptions{}, 1)) << "cloud " << cloud;
  }
}

TEST(OffsetParticleFilter, Errors) {
  const NoiseSchedule s = noise_schedule_preset("paper");
  EXPECT_EQ(error_of([&] { OffsetParticleFilter(7, 0, s, 1); }),
            "body schema filter: M must be >= 1, got 0");
  EXPECT_EQ(error_of([&] { OffsetParticleFilter(0, 10, s, 1); }),
            "body schema filter: need at least one offset, got 0");
  OffsetParticleFilter f(7, 3, s, 1);
  EXPECT_EQ(error_of([&] {
              f.update({1.0, 1.0});
            }),
            "body schema filter: expected 3 likelihoods, got 2");
  EXPECT_EQ(error_of([&] {
              f.update({1.0, -0.5, 1.0});
            }),
            "body schema filter: likelihood of particle 1 is -0.5 (expected finite and >= 0)");
  EXPECT_EQ(error_of([&] { f.set_particles(Eigen::MatrixXd::Zero(7, 4)); }),
            "body schema filter: particles must be 7 x 3, got 7 x 4");
  KdeOptions no_keep;
  no_keep.screen_keep = 0;
  EXPECT_EQ(error_of([&] { OffsetParticleFilter(7, 10, s, 1, no_keep); }),
            "body schema filter: KDE exact limit, screen samples and screen keep must be >= 1, "
            "got 4096, 512 and 0");
}

}  // namespace
}  // namespace somasim::body_schema
