// ContactEvidenceLog: an estimate only from enough agreeing values, the mean of those that agree
// with the median; generated values with injected outliers never give an absurd estimate.
#include <random>

#include <gtest/gtest.h>

#include "somasim/pps/contact_evidence.hpp"

using namespace somasim::pps;

TEST(PpsContactEvidence, TooFewOrDisagreeingValuesGiveNoEstimate) {
  ContactEvidenceLog log;
  log.resize(3);
  const ContactEstimateSpec spec;  // 2 events, 2 cm
  EXPECT_EQ(log.state(0, spec), ContactEvidence::kNone);
  log.add(0, 0.012);
  EXPECT_EQ(log.state(0, spec), ContactEvidence::kTooFew);
  EXPECT_FALSE(log.estimate(0, spec));
  log.add(0, 0.016);
  EXPECT_EQ(log.state(0, spec), ContactEvidence::kEstimated);
  EXPECT_NEAR(*log.estimate(0, spec), 0.014, 1e-15);
  // Two values 84 cm apart: neither is a majority.
  log.add(1, 0.01);
  log.add(1, 0.85);
  EXPECT_EQ(log.state(1, spec), ContactEvidence::kTooFew);
  log.add(1, 0.40);
  EXPECT_EQ(log.state(1, spec), ContactEvidence::kTooFew);
  // Three agreeing values and one absurd one: the absurd one is left out.
  for (const double d : {0.010, 0.012, 0.014, 0.84}) log.add(2, d);
  EXPECT_NEAR(*log.estimate(2, spec), 0.012, 1e-15);
  EXPECT_EQ(log.count(2), 4u);
  EXPECT_NEAR(log.sum(2), 0.876, 1e-12);
}

TEST(PpsContactEvidence, HalfTheValuesOutsideTheAgreementIsDisagreeing) {
  ContactEvidenceLog log;
  log.resize(1);
  // Median 0.012: three of seven values within 1 cm of it.
  for (const double d : {0.0, 0.004, 0.008, 0.012, 0.04, 0.05, 0.06}) log.add(0, d);
  ContactEstimateSpec spec;
  spec.agreement_m = 0.01;
  EXPECT_EQ(log.state(0, spec), ContactEvidence::kDisagreeing);
}

TEST(PpsContactEvidence, RestoredEvidenceIsItsMeanOnceThereIsEnough) {
  ContactEvidenceLog log;
  log.resize(2);
  log.restore(0, 0.03, 2);
  log.restore(1, 0.02, 1);
  const ContactEstimateSpec spec;
  EXPECT_NEAR(*log.estimate(0, spec), 0.015, 1e-15);
  EXPECT_EQ(log.state(1, spec), ContactEvidence::kTooFew);
}

// Generated: a true offset, 2-12 values with 1 cm noise, up to a third replaced by outliers up
// to a metre away. Whenever there is an estimate it is within 2 cm of the truth.
TEST(PpsContactEvidence, OutliersNeverMakeAnAbsurdEstimate) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.005);
  const ContactEstimateSpec spec;
  int estimated = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    ContactEvidenceLog log;
    log.resize(1);
    const double truth = 0.1 * (u(rng) - 0.5);
    const int n = 2 + static_cast<int>(u(rng) * 11);
    const int outliers = static_cast<int>(u(rng) * (n / 3 + 1));
    for (int i = 0; i < n; ++i)
      log.add(0, i < outliers ? truth + (u(rng) < 0.5 ? -1 : 1) * (0.05 + 0.95 * u(rng))
                              : truth + noise(rng));
    if (const auto e = log.estimate(0, spec)) {
      ++estimated;
      EXPECT_NEAR(*e, truth, 0.02) << "n " << n << ", outliers " << outliers;
    }
  }
  EXPECT_GT(estimated, 1500);
}
