// Pressure models and contact episodes of one skin part.
#include <gtest/gtest.h>

#include <cmath>

#include "somasim/skin/skin_response.hpp"

using namespace somasim::skin;

namespace {

// A 5 x 5 grid, 5 mm apart, in the z = 0 plane; modules of the 5 columns.
SkinLayout grid() {
  SkinLayout l;
  l.body_part = "patch";
  l.link = 0;
  std::vector<int> keys;
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 5; ++c) {
      l.ids.push_back(r * 5 + c);
      l.positions.emplace_back(0.005 * c, 0.005 * r, 0.0);
      l.normals.emplace_back(0, 0, 1);
      keys.push_back(100 + c);
    }
  group_by_key(l, keys);
  return l;
}

}  // namespace

TEST(SkinResponse, SharedModelSplitsTheForceAmongTaxelsInTheRadius) {
  const SkinLayout l = grid();
  ResponseParams p;
  p.contact_radius = 0.0051;  // the centre taxel and its 4 neighbours
  PartResponse r(l, p);
  EXPECT_EQ(r.add_contact({0.01, 0.01, 0.0}, 1.0), 5);
  double sum = 0.0;
  for (double x : r.pressures()) sum += x;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_NEAR(r.pressures()[12], 0.2, 1e-12);
  EXPECT_NEAR(r.virtual_pressure(2), 0.2, 1e-12);
  EXPECT_EQ(r.pressures()[0], 0.0);
}

TEST(SkinResponse, KernelModelPeaksAtTheContact) {
  const SkinLayout l = grid();
  ResponseParams p;
  p.contact_radius = 0.01;
  p.model = PressureModel::kKernel;
  PartResponse r(l, p);
  r.add_contact({0.01, 0.01, 0.0}, 2.0);
  EXPECT_NEAR(r.pressures()[12], 2.0, 1e-12);
  EXPECT_NEAR(r.pressures()[13], 2.0 * std::exp(-0.5), 1e-12);  // d = σ = 5 mm
  EXPECT_EQ(r.pressures()[0], 0.0) << "outside the radius";
}

TEST(SkinResponse, OneEventPerEpisodeWithTheTouchedVirtualTaxels) {
  const SkinLayout l = grid();
  ResponseParams p;
  p.contact_radius = 0.0051;
  p.pressure_threshold = 0.1;
  p.release_s = 0.1;
  PartResponse r(l, p);
  double t = 0.0;
  const auto tick = [&](double force) {
    r.clear();
    if (force > 0) r.add_contact({0.01, 0.01, 0.0}, force);
    auto onset = r.update(t);
    t += 0.02;
    return onset;
  };
  EXPECT_FALSE(tick(0.0));
  const auto onset = tick(1.0);
  ASSERT_TRUE(onset);
  EXPECT_EQ(onset->physical_count, 5);
  EXPECT_EQ(onset->virtual_ids, (std::vector<int>{101, 102, 103}));
  for (int k = 0; k < 20; ++k) EXPECT_FALSE(tick(1.0)) << "persistent contact: no new event";
  EXPECT_FALSE(tick(0.0)) << "a short gap (bounce) keeps the episode";
  EXPECT_FALSE(tick(1.0));
  for (int k = 0; k < 6; ++k) tick(0.0);
  EXPECT_FALSE(r.in_episode());
  EXPECT_TRUE(tick(1.0)) << "a new episode after release_s";
}

TEST(SkinResponse, NoEventBelowThresholdOrOnTooFewTaxels) {
  const SkinLayout l = grid();
  ResponseParams p;
  p.contact_radius = 0.0051;
  p.pressure_threshold = 0.1;
  {
    PartResponse r(l, p);
    r.add_contact({0.01, 0.01, 0.0}, 0.5);  // 0.1 per taxel: not above the threshold
    EXPECT_FALSE(r.update(0.0));
  }
  {
    PartResponse r(l, p);
    r.add_contact({0.0, 0.0, 0.0}, 1.0);  // the corner: 3 taxels in the radius
    EXPECT_TRUE(r.update(0.0)) << "3 > min_taxels = 2";
  }
  {
    PartResponse r(l, p);
    r.add_contact({-0.0025, 0.0, 0.0}, 1.0);  // off the corner: 2 taxels
    EXPECT_FALSE(r.update(0.0));
    EXPECT_EQ(r.over_threshold()[0], true);
  }
}

TEST(SkinResponse, OnsetCarriesTheCentreOfPressure) {
  const SkinLayout l = grid();
  ResponseParams p;
  p.contact_radius = 0.0076;  // the 3 x 3 block around a taxel and no further
  p.model = PressureModel::kKernel;
  PartResponse r(l, p);
  r.add_contact({0.01, 0.01, 0.0}, 1.0);  // on taxel 12: a symmetric block
  const auto onset = r.update(0.0);
  ASSERT_TRUE(onset.has_value());
  EXPECT_LT((onset->centre_link - Eigen::Vector3d(0.01, 0.01, 0.0)).norm(), 1e-12);
  EXPECT_LT((onset->normal_link - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
}

TEST(SkinResponse, CentreOfPressureFollowsAContactBetweenTaxels) {
  const SkinLayout l = grid();
  ResponseParams p;
  p.contact_radius = 0.0051;
  PartResponse r(l, p);
  // Between taxels 12 and 13 and pressing 13 harder: two contact points of one touch.
  r.add_contact({0.0125, 0.01, 0.0}, 1.0);
  r.add_contact({0.015, 0.01, 0.0}, 1.0);
  const auto onset = r.update(0.0);
  ASSERT_TRUE(onset.has_value());
  EXPECT_GT(onset->centre_link.x(), 0.0125);
  EXPECT_LT(onset->centre_link.x(), 0.015);
  EXPECT_NEAR(onset->centre_link.y(), 0.01, 1e-12);
}
