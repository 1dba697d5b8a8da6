// Generated skin layouts: taxels on the surface, outward unit normals, spacing, counts, modules.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <set>

#include "somasim/error.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/skin/skin_layout.hpp"

using somasim::robot::SkinPatch;
using somasim::skin::generate_layout;
using somasim::skin::LayoutOptions;
using somasim::skin::SkinLayout;

namespace {

// A forearm-like half cylinder whose axis runs along -y of the link (as on the iCub's left arm).
SkinPatch forearm(double spacing, int group_size = 1) {
  SkinPatch p;
  p.body_part = "left_forearm";
  p.link = 3;
  p.surface = "cylinder";
  p.origin = Eigen::Isometry3d(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()));
  p.origin.translation() = Eigen::Vector3d(0.001, 0.002, 0.003);
  p.params = {{"radius", 0.021},
              {"z_min", 0.02},
              {"z_max", 0.13},
              {"angle_min_deg", 90.0},
              {"angle_max_deg", 270.0},
              {"spacing", spacing},
              {"group_size", double(group_size)}};
  return p;
}

SkinPatch palm(double spacing, int group_size = 1) {
  SkinPatch p;
  p.body_part = "right_palm";
  p.link = 5;
  p.surface = "box_face";
  p.origin = Eigen::Isometry3d(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 1, 0).normalized()));
  p.origin.translation() = Eigen::Vector3d(-0.03, 0, 0);
  p.params = {
      {"size_x", 0.05}, {"size_y", 0.04}, {"spacing", spacing}, {"group_size", double(group_size)}};
  return p;
}

double nearest_neighbour(const SkinLayout& l, std::size_t i) {
  double best = 1e9;
  for (std::size_t j = 0; j < l.size(); ++j)
    if (j != i) best = std::min(best, (l.positions[i] - l.positions[j]).norm());
  return best;
}

}  // namespace

TEST(SkinLayout, CylinderTaxelsLieOnTheSurfaceWithOutwardUnitNormals) {
  const SkinPatch patch = forearm(0.005);
  const SkinLayout l = generate_layout(patch);
  ASSERT_GT(l.size(), 100u);
  EXPECT_EQ(l.body_part, "left_forearm");
  EXPECT_EQ(l.link, 3);
  const Eigen::Isometry3d to_surface = patch.origin.inverse();
  for (std::size_t i = 0; i < l.size(); ++i) {
    const Eigen::Vector3d s = to_surface * l.positions[i];
    const Eigen::Vector3d n = patch.origin.linear().transpose() * l.normals[i];
    EXPECT_NEAR(std::hypot(s.x(), s.y()), 0.021, 1e-12);
    EXPECT_GE(s.z(), 0.02 - 1e-12);
    EXPECT_LE(s.z(), 0.13 + 1e-12);
    EXPECT_LE(s.x(), 1e-12) << "angles 90..270 deg: the -x half";
    EXPECT_NEAR(l.normals[i].norm(), 1.0, 1e-12);
    // Outward: along the radial direction, no axial component.
    EXPECT_NEAR(n.z(), 0.0, 1e-12);
    EXPECT_NEAR(n.head<2>().dot(s.head<2>().normalized()), 1.0, 1e-12);
  }
}

TEST(SkinLayout, BoxFaceTaxelsLieOnTheFaceWithItsNormal) {
  const SkinPatch patch = palm(0.005);
  const SkinLayout l = generate_layout(patch);
  EXPECT_EQ(l.size(), 11u * 9u);
  const Eigen::Isometry3d to_face = patch.origin.inverse();
  for (std::size_t i = 0; i < l.size(); ++i) {
    const Eigen::Vector3d s = to_face * l.positions[i];
    EXPECT_NEAR(s.z(), 0.0, 1e-12);
    EXPECT_LE(std::abs(s.x()), 0.025 + 1e-12);
    EXPECT_LE(std::abs(s.y()), 0.02 + 1e-12);
    EXPECT_TRUE(l.normals[i].isApprox(patch.origin.linear().col(2), 1e-12));
  }
}

TEST(SkinLayout, SpacingIsRespected) {
  for (double spacing : {0.004, 0.007, 0.01}) {
    for (const SkinPatch& patch : {forearm(spacing), palm(spacing)}) {
      const SkinLayout l = generate_layout(patch);
      for (std::size_t i = 0; i < l.size(); ++i) {
        // Box: exact; cylinder: the chord of an arc of length `spacing`, a little shorter.
        const double chord =
            patch.surface == "cylinder" ? 2 * 0.021 * std::sin(spacing / 0.042) : spacing;
        const double d = nearest_neighbour(l, i);
        EXPECT_GT(d, chord - 1e-12) << patch.body_part << " taxel " << i;
        EXPECT_LT(d, spacing + 1e-12) << patch.body_part << " taxel " << i;
      }
    }
  }
}

TEST(SkinLayout, CountsScaleWithSpacing) {
  const auto count = [](double s) { return generate_layout(forearm(s)).size(); };
  // Half the spacing: about four times the taxels.
  const double ratio = double(count(0.0025)) / double(count(0.005));
  EXPECT_GT(ratio, 3.5);
  EXPECT_LT(ratio, 4.5);
  EXPECT_GT(count(0.01), count(0.02));
  // A spacing larger than the patch still leaves one taxel (in the middle).
  EXPECT_EQ(generate_layout(palm(1.0)).size(), 1u);
}

TEST(SkinLayout, FullTurnCylinderClosesWithoutOverlap) {
  SkinPatch patch = forearm(0.004);
  patch.params["angle_min_deg"] = -180;
  patch.params["angle_max_deg"] = 180;
  const SkinLayout l = generate_layout(patch);
  for (std::size_t i = 0; i < l.size(); ++i) EXPECT_GT(nearest_neighbour(l, i), 0.99 * 0.004);
}

TEST(SkinLayout, FourThousandTaxelsQuickly) {
  SkinPatch whole_arm = forearm(0.0025, 10);
  whole_arm.params["angle_min_deg"] = -180;
  whole_arm.params["angle_max_deg"] = 180;
  whole_arm.params["z_max"] = 0.30;
  const auto t0 = std::chrono::steady_clock::now();
  const SkinLayout l = generate_layout(whole_arm);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GE(l.size(), 4000u);
  EXPECT_LT(ms, 1000.0) << "generous bound: it takes about a millisecond";
  EXPECT_NEAR(double(l.size()) / double(l.virtual_taxels.size()), 10.0, 1.5);
}

TEST(SkinLayout, EveryTaxelIsInExactlyOneModule) {
  for (int group : {1, 4, 10, 12}) {
    for (const SkinPatch& patch : {forearm(0.004, group), palm(0.004, group)}) {
      const SkinLayout l = generate_layout(patch);
      std::vector<int> seen(l.size(), 0);
      std::set<int> ids;
      for (std::size_t v = 0; v < l.virtual_taxels.size(); ++v) {
        const auto& vt = l.virtual_taxels[v];
        EXPECT_TRUE(ids.insert(vt.id).second) << "virtual ids are unique";
        ASSERT_FALSE(vt.members.empty());
        EXPECT_NE(std::find(vt.members.begin(), vt.members.end(), vt.centre), vt.members.end());
        for (int m : vt.members) {
          ++seen[static_cast<std::size_t>(m)];
          EXPECT_EQ(l.module[static_cast<std::size_t>(m)], static_cast<int>(v));
        }
        EXPECT_TRUE(l.virtual_position(v).isApprox(l.positions[vt.centre]));
        EXPECT_TRUE(l.virtual_normal(v).isApprox(l.normals[vt.centre]));
      }
      for (int s : seen) EXPECT_EQ(s, 1);
      const double mean = double(l.size()) / double(l.virtual_taxels.size());
      EXPECT_NEAR(mean, group, 0.35 * group + 0.5) << patch.body_part << " group " << group;
    }
  }
}

TEST(SkinLayout, ModulesAreCompactNeighbourhoods) {
  const double spacing = 0.004;
  const SkinLayout l = generate_layout(forearm(spacing, 10));
  for (const auto& vt : l.virtual_taxels)
    for (int m : vt.members)  // blocks of about 3 x 4 taxels: within 2.5 spacings of the centre
      EXPECT_LT((l.positions[m] - l.positions[vt.centre]).norm(), 2.6 * spacing);
}

TEST(SkinLayout, GroupSizeOneKeepsEveryTaxel) {
  const SkinLayout l = generate_layout(palm(0.01));
  ASSERT_EQ(l.virtual_taxels.size(), l.size());
  for (std::size_t i = 0; i < l.size(); ++i) EXPECT_EQ(l.virtual_taxels[i].centre, int(i));
}

TEST(SkinLayout, OptionsOverrideThePatch) {
  LayoutOptions o;
  o.spacing = 0.01;
  o.group_size = 4;
  const SkinLayout l = generate_layout(palm(0.005), o);
  EXPECT_EQ(l.size(), 6u * 5u);
  EXPECT_LT(l.virtual_taxels.size(), l.size());
}

TEST(SkinLayout, SurfaceCoordinatesUnrollTheCylinder) {
  const SkinPatch patch = forearm(0.005);
  const SkinLayout l = generate_layout(patch);
  const auto uv = somasim::skin::surface_coordinates(patch, l.positions);
  ASSERT_EQ(uv.size(), l.size());
  for (const auto& p : uv) {
    EXPECT_GE(p.x(), 0.021 * std::numbers::pi / 2 - 1e-9);
    EXPECT_LE(p.x(), 0.021 * 3 * std::numbers::pi / 2 + 1e-9);
    EXPECT_GE(p.y(), 0.02 - 1e-9);
  }
  // Neighbours in a row are `spacing` apart in the unrolled plane.
  EXPECT_NEAR((uv[1] - uv[0]).norm(), 0.005, 1e-9);
}

TEST(SkinLayout, BadPatchesAreInputErrors) {
  SkinPatch p = palm(0.01);
  p.params.erase("size_y");
  try {
    generate_layout(p);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(), "skin patch 'right_palm': missing parameter 'size_y'");
  }
  p = palm(0.01);
  p.surface = "sphere";
  try {
    generate_layout(p);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "skin patch 'right_palm': unknown surface 'sphere'; expected one of: cylinder, "
                 "box_face");
  }
  p = palm(0.01);
  LayoutOptions o;
  o.spacing = 1e-6;
  try {
    generate_layout(p, o);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "skin patch 'right_palm': spacing 1e-06 m gives 2000090001 taxels; expected at "
                 "most 5e6");
  }
}

TEST(SkinLayout, IcubPatchesGenerate) {
  const auto model =
      somasim::robot::load_robot_model_shared(SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml");
  for (const auto& patch : model->skin_patches()) {
    const SkinLayout l = generate_layout(patch);
    EXPECT_GT(l.size(), 3u) << patch.body_part;
    EXPECT_EQ(l.link, patch.link);
  }
}

// Spacings down to the smallest double and group sizes of any magnitude: refused with an error
// (too many taxels, no integer group size) on every surface, never a wrapped count.
TEST(SkinLayout, ExtremeSpacingsAndGroupSizesAreRefused) {
  for (double spacing = 1e-5; spacing > 0; spacing /= 1e7) {
    for (const SkinPatch& p : {forearm(spacing), palm(spacing)}) {
      try {
        generate_layout(p);
        ADD_FAILURE() << p.surface << " spacing " << spacing << ": no error";
      } catch (const somasim::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("expected at most 5e6"), std::string::npos)
            << e.what();
      }
    }
  }
  for (const double g : {0.0, -3.0, 1e10, 1e300, -1e300, std::nan("")}) {
    SkinPatch p = palm(0.01);
    p.params["group_size"] = g;
    EXPECT_THROW(generate_layout(p), somasim::InputError) << g;
  }
}
