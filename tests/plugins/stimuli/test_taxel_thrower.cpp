// taxel_thrower: throws, hit rule, perceived offset and noise, stop, determinism.
#include <gtest/gtest.h>

#include "somasim/pps/ports.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/testing/harness.hpp"

using somasim::ContactEvents;
using somasim::pps::Stimulus;
using somasim::testing::Harness;

namespace {

std::string thrower(const std::string& params) {
  return "base_rate_hz: 20\nnodes:\n  t: {plugin: taxel_thrower, params: {" + params + "}}\n";
}

int run_to_end(Harness& h) {
  int ticks = 0;
  while (h.step()) ++ticks;
  h.finish();
  return ticks;
}

}  // namespace

TEST(TaxelThrower, StopsAfterTheRequestedThrowsWithOneContactEach) {
  Harness h(thrower("throws: 7"));
  std::uint64_t last_id = 0;
  int contacts = 0;
  while (h.step())
    for (const auto& e : h.output<ContactEvents>("t.contacts").recent)
      if (e.id > last_id) {
        last_id = e.id;
        ++contacts;
        EXPECT_EQ(e.body_part, "taxel");
      }
  h.finish();
  EXPECT_EQ(contacts, 7);
  EXPECT_EQ(h.metric("t", "throws"), 7);
}

TEST(TaxelThrower, LandingOnTheTaxelIsAlwaysAHitAndFarAwayNever) {
  Harness on(thrower("throws: 20, landing_sigma: 0"));
  run_to_end(on);
  EXPECT_EQ(on.metric("t", "hit_rate"), 1.0);
  Harness off(thrower("throws: 20, landing_sigma: 0.5, hit_radius: 0"));
  run_to_end(off);
  EXPECT_EQ(off.metric("t", "hit_rate"), 0.0);
}

TEST(TaxelThrower, ApproachesFromTheStartZoneAtTheDrawnSpeed) {
  Harness h(
      thrower("throws: 1, landing_sigma: 0, speed_min: 0.1, speed_max: 0.1, start_cone_deg: 0"));
  ASSERT_TRUE(h.step());
  const Stimulus& s = h.output<Stimulus>("t.truth");
  EXPECT_TRUE(s.present);
  EXPECT_NEAR(s.position.x(), 0.0, 1e-12);
  EXPECT_GE(s.position.z(), 0.25);
  EXPECT_LE(s.position.z(), 0.30);
  EXPECT_NEAR(s.velocity.z(), -0.1, 1e-12);
  const double z0 = s.position.z();
  ASSERT_TRUE(h.step());
  EXPECT_NEAR(h.output<Stimulus>("t.truth").position.z(), z0 - 0.1 * 0.05, 1e-12);
}

TEST(TaxelThrower, PerceivedStimulusCarriesTheSystematicOffsetAlongTheNormal) {
  Harness h(thrower("throws: 5, offset: -0.1, landing_sigma: 0"));
  ASSERT_TRUE(h.step());
  const Stimulus& truth = h.output<Stimulus>("t.truth");
  const Stimulus& seen = h.output<Stimulus>("t.stimulus");
  EXPECT_NEAR(seen.position.z() - truth.position.z(), -0.1, 1e-12);
  run_to_end(h);
  // Every throw lands on the taxel: the perceived contact is 10 cm behind the skin.
  EXPECT_NEAR(h.metric("t", "contact_distance_m").get<double>(), -0.1, 1e-9);
}

TEST(TaxelThrower, NoiseIsZeroMeanWithTheRequestedSpread) {
  Harness h(thrower("throws: 50, position_noise: 0.01"));
  double sum = 0, sum2 = 0;
  int n = 0;
  while (h.step()) {
    const double e =
        h.output<Stimulus>("t.stimulus").position.x() - h.output<Stimulus>("t.truth").position.x();
    sum += e;
    sum2 += e * e;
    ++n;
  }
  EXPECT_GT(n, 1000);
  EXPECT_NEAR(sum / n, 0.0, 0.002);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.01, 0.001);
}

TEST(TaxelThrower, SameSeedSameThrowsOtherSeedOthers) {
  auto trace = [](int seed) {
    somasim::LoadOptions o;
    o.seed = seed;
    Harness h(thrower("throws: 3, position_noise: 0.001"), {}, o);
    std::vector<double> xs;
    while (h.step()) xs.push_back(h.output<Stimulus>("t.stimulus").position.x());
    return xs;
  };
  EXPECT_EQ(trace(4), trace(4));
  EXPECT_NE(trace(4), trace(5));
}

TEST(TaxelThrower, RejectsInconsistentRanges) {
  try {
    Harness h(thrower("speed_min: 0.2, speed_max: 0.1"));
    FAIL() << "expected an InputError";
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(
        e.what(),
        "<inline>:3:66: node 't', key 'params.speed_max': must not be less than speed_min");
  }
}
