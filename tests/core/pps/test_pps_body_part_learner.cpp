#include <vector>

#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/pps/body_part_learner.hpp"

using namespace somasim::pps;

namespace {

// Two taxels on a flat patch (link frame), normals +z, 5 cm apart.
std::vector<TaxelInfo> two_taxels() {
  return {TaxelInfo{10, TaxelPose{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d::UnitZ()}},
          TaxelInfo{11, TaxelPose{Eigen::Vector3d(0.05, 0, 0), Eigen::Vector3d::UnitZ()}}};
}

// An object approaching taxel 10 along -z at 0.1 m/s, 50 ms samples, from z = 0.15 m.
void approach(BodyPartLearner& l, const Eigen::Isometry3d& root_from_link, double t0 = 0.0) {
  for (int i = 0; i < 30; ++i) {
    const double z = 0.15 - 0.1 * 0.05 * i;
    Stimulus s{root_from_link * Eigen::Vector3d(0, 0, z),
               root_from_link.linear() * Eigen::Vector3d(0, 0, -0.1), 0.0};
    l.push_stimulus(StimulusSample{t0 + 0.05 * i, s});
  }
}

}  // namespace

TEST(PpsBodyPartLearner, PositivesForTouchedNegativesForOthers) {
  BodyPartLearner l("l_forearm", two_taxels(), LearnerParams::paper());
  const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  approach(l, pose);
  const std::vector<int> touched = {10};
  const LearningStats st = l.on_contact(pose, touched);
  EXPECT_EQ(st.buffered_samples, 30u);
  EXPECT_EQ(st.touched_taxels, 1u);
  // Taxel 10: every sample is on its normal, in the RF, approaching, D in (0.005, 0.15].
  EXPECT_EQ(st.positives, 30u);
  EXPECT_GT(st.negatives, 0u);
  EXPECT_EQ(st.behind_skin, 0u);
  EXPECT_TRUE(l.buffer().empty());
  std::uint32_t pos0 = 0, neg0 = 0, pos1 = 0, neg1 = 0;
  for (std::size_t k = 0; k < 32; ++k) {
    pos0 += l.maps()[0].pos()[k];
    neg0 += l.maps()[0].neg()[k];
    pos1 += l.maps()[1].pos()[k];
    neg1 += l.maps()[1].neg()[k];
  }
  EXPECT_EQ(pos0, 30u);
  EXPECT_EQ(neg0, 0u);
  EXPECT_EQ(pos1, 0u);
  EXPECT_EQ(neg1, st.negatives);
  // The sample at D = 0.10 m, TTC = 1.0 s went to the expected bin of taxel 10.
  int i = 0, j = 0;
  ASSERT_TRUE(l.params().grid.bin_of(0.10, 1.0, i, j));
  EXPECT_GT(l.maps()[0].pos()[l.params().grid.index(i, j)], 0u);
  EXPECT_GT(l.maps()[0].activation(0.05, 0.5), 0.5);
  EXPECT_EQ(l.maps()[1].activation(0.05, 0.5), 0.0);
}

TEST(PpsBodyPartLearner, PosedLinkAndExplicitRootPosesAgree) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  pose.pretranslate(Eigen::Vector3d(0.3, -0.2, 0.5));
  BodyPartLearner a("p", two_taxels(), LearnerParams::code());
  BodyPartLearner b("p", two_taxels(), LearnerParams::code());
  approach(a, pose);
  approach(b, pose);
  std::vector<TaxelPose> root;
  for (const TaxelInfo& t : two_taxels())
    root.push_back(TaxelPose{pose * t.pose_link.position, pose.linear() * t.pose_link.normal});
  const std::vector<int> touched = {10};
  const LearningStats sa = a.on_contact(pose, touched);
  const LearningStats sb = b.on_contact(root, touched);
  EXPECT_EQ(sa.positives, sb.positives);
  EXPECT_EQ(sa.negatives, sb.negatives);
  EXPECT_GE(sa.positives, 23u);  // code grid: TTC <= 1.2 s, i.e. z <= 0.12 m
  EXPECT_EQ(sa.out_of_range, sb.out_of_range);
  EXPECT_EQ(a.maps()[0].pos(), b.maps()[0].pos());
}

TEST(PpsBodyPartLearner, RecedingStimulusTeachesNothingWithSignedTtc) {
  BodyPartLearner l("p", two_taxels(), LearnerParams::paper());
  for (int i = 0; i < 20; ++i)
    l.push_stimulus(StimulusSample{
        0.05 * i, Stimulus{Eigen::Vector3d(0, 0, 0.02 + 0.005 * i), Eigen::Vector3d(0, 0, 0.1)}});
  const std::vector<int> touched = {10};
  const LearningStats st = l.on_contact(Eigen::Isometry3d::Identity(), touched);
  EXPECT_EQ(st.positives + st.negatives, 0u);
  EXPECT_GT(st.invalid_ttc, 0u);
}

TEST(PpsBodyPartLearner, BehindSkinCountedWithMirroredRf) {
  LearnerParams p = LearnerParams::code();
  p.ttc = TtcDefinition::kUnsigned;
  BodyPartLearner l("p", two_taxels(), p);
  l.push_stimulus(
      StimulusSample{0.0, Stimulus{Eigen::Vector3d(0, 0, -0.03), Eigen::Vector3d(0, 0, -0.1)}});
  const std::vector<int> touched = {10};
  const LearningStats st = l.on_contact(Eigen::Isometry3d::Identity(), touched);
  EXPECT_EQ(st.positives, 1u);
  EXPECT_EQ(st.behind_skin, 2u);  // counted by both taxels (negative for taxel 11)
}

TEST(PpsBodyPartLearner, WrongPoseCountIsInputError) {
  BodyPartLearner l("l_forearm", two_taxels(), LearnerParams::paper());
  const std::vector<TaxelPose> poses(3);
  try {
    l.on_contact(poses, std::vector<int>{10});
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "PPS learner 'l_forearm': contact event gives 3 taxel poses, expected 2 (one "
                 "per taxel of the body part)");
  }
}
