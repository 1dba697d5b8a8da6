// The `contact` offset estimator (perceived D minus the skin's own D, kOffsetClearance outside
// the taxel on the way in) against the truth of true_offsets.hpp.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "somasim/pps/body_part_learner.hpp"
#include "somasim/pps/true_offsets.hpp"

using namespace somasim::pps;

namespace {

constexpr double kRadius = 0.02;                     // [m]
const Eigen::Vector3d kContact(0.012, -0.004, 0.0);  // touch point, link frame
const Eigen::Vector3d kVelocity(0.01, 0.0, -0.1);    // [m/s]
constexpr double kTouchTime = 3.0;                   // [s]
const TaxelPose kTrueTaxel{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()};

// The object (root frame = the true link frame) touches the skin at kContact at kTouchTime.
Stimulus object_at(double t) {
  Stimulus s;
  s.position = kContact + Eigen::Vector3d(0, 0, kRadius) + kVelocity * (t - kTouchTime);
  s.velocity = kVelocity;
  s.radius = kRadius;
  s.present = true;
  return s;
}

// One touch measures the offset: the evidence rule (contact_evidence.hpp, tested there) set to
// accept a single event.
LearnerParams one_event() {
  LearnerParams p = LearnerParams::code();
  p.contact.min_events = 1;
  return p;
}

double d_of(const TaxelPose& taxel, const Stimulus& s) {
  const TaxelFrameStimulus local = to_taxel_frame(taxel, s);
  return compute_d_ttc(local.p, local.v, TtcDefinition::kUnsigned).d;
}

// The truth: both D where the object was kOffsetClearance outside the true taxel (0.5 s before).
double true_offset(const TaxelPose& believed) {
  const double t = kTouchTime - kOffsetClearance / -kVelocity.z();
  return d_of(believed, object_at(t)) - d_of(kTrueTaxel, object_at(t));
}

// 50 ms samples from 2 s before the touch up to 25 ms before it.
void approach(BodyPartLearner& l) {
  for (int i = 0; i < 40; ++i) {
    const double t = kTouchTime - 2.0 + 0.025 + 0.05 * i;
    l.push_stimulus(StimulusSample{t, object_at(t)});
  }
}

// One touch with the taxel believed at `believed` (root frame); the contact estimate.
double one_touch(const TaxelPose& believed, bool with_touch_point) {
  BodyPartLearner l("patch", {TaxelInfo{7, kTrueTaxel}}, one_event());
  approach(l);
  std::optional<SkinTouch> touch;
  if (with_touch_point) touch = SkinTouch{kContact, Eigen::Vector3d::UnitZ()};
  const std::vector<TaxelPose> poses = {believed};
  const std::vector<int> touched = {7};
  l.record_contact_offset(poses, touched, kTouchTime, touch);
  return l.contact_offset(0).value();
}

}  // namespace

TEST(PpsContactOffset, EqualsTheTrueOffsetForErrorsOfEitherSign) {
  // Believed taxel poses: along the normal (either sign), sideways, tilted.
  std::vector<TaxelPose> believed;
  for (const double dz : {-0.025, -0.01, 0.01, 0.025})
    believed.push_back({Eigen::Vector3d(0, 0, dz), Eigen::Vector3d::UnitZ()});
  believed.push_back({Eigen::Vector3d(0.02, 0.005, -0.01), Eigen::Vector3d::UnitZ()});
  believed.push_back({Eigen::Vector3d(-0.008, 0, 0.012), Eigen::Vector3d(0.1, 0, 1).normalized()});
  for (const TaxelPose& b : believed)
    EXPECT_NEAR(one_touch(b, true), true_offset(b), 1e-9)
        << "believed at " << b.position.transpose();
}

TEST(PpsContactOffset, ASidewaysErrorIsNotASignFlip) {
  // 2 cm sideways, in the skin plane: at the contact D would be ±2 cm by the sign of p_z ≈ 0;
  // 5 cm out it is the small change of distance the shift makes.
  const TaxelPose sideways{Eigen::Vector3d(0.02, 0, 0), Eigen::Vector3d::UnitZ()};
  const double truth = true_offset(sideways);
  EXPECT_GT(truth, 0.0);
  EXPECT_LT(truth, 0.006);
  EXPECT_NEAR(one_touch(sideways, true), truth, 1e-9);
}

TEST(PpsContactOffset, WithoutTheTouchPointItIsTheDAtTheTouch) {
  // No centre of pressure: the perceived D at the touch, the sideways distance of the contact
  // from the taxel centre included (|(0.012, -0.004)| = 12.6 mm).
  EXPECT_NEAR(one_touch(kTrueTaxel, false), kContact.norm(), 1e-9);
  EXPECT_NEAR(one_touch(kTrueTaxel, true), 0.0, 1e-9);
}

TEST(PpsContactOffset, CreditsTheTaxelNearestTheCentreOfPressure) {
  std::vector<TaxelInfo> taxels;
  for (int i = 0; i < 4; ++i)
    taxels.push_back({i, TaxelPose{Eigen::Vector3d(0.015 * i, 0, 0), Eigen::Vector3d::UnitZ()}});
  BodyPartLearner l("patch", taxels, one_event());
  approach(l);
  std::vector<TaxelPose> poses;  // believed 1 cm inside, exactly translated
  for (const auto& t : taxels)
    poses.push_back({t.pose_link.position - Eigen::Vector3d(0, 0, 0.01), t.pose_link.normal});
  const std::vector<int> touched = {0, 1, 2};
  l.record_contact_offset(poses, touched, kTouchTime,
                          SkinTouch{kContact, Eigen::Vector3d::UnitZ()});
  EXPECT_EQ(l.contact_count(0), 0u);
  EXPECT_EQ(l.contact_count(1), 1u);  // 0.015 m is nearest 0.012 m
  EXPECT_EQ(l.contact_count(2), 0u);
  const TaxelPose true_taxel{Eigen::Vector3d(0.015, 0, 0), Eigen::Vector3d::UnitZ()};
  const double t = kTouchTime - 0.5;
  EXPECT_NEAR(l.contact_offset(1).value(),
              d_of(poses[1], object_at(t)) - d_of(true_taxel, object_at(t)), 1e-9);
}

TEST(PpsContactOffset, ToleratesARotatedBelievedLinkPose) {
  // A patch of taxels whose believed link pose is 3 degrees and 1 cm off: the path is carried
  // into the link frame by the fitted pose; within 1 mm of the truth.
  std::vector<TaxelInfo> taxels;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      taxels.push_back({3 * i + j, TaxelPose{Eigen::Vector3d(0.015 * (i - 1), 0.015 * (j - 1), 0),
                                             Eigen::Vector3d::UnitZ()}});
  Eigen::Isometry3d believed = Eigen::Isometry3d::Identity();
  believed.rotate(Eigen::AngleAxisd(3.0 * M_PI / 180, Eigen::Vector3d(1, 1, 0).normalized()));
  believed.pretranslate(Eigen::Vector3d(0.004, -0.003, -0.01));
  BodyPartLearner l("patch", taxels, one_event());
  approach(l);
  std::vector<TaxelPose> poses;
  for (const auto& t : taxels)
    poses.push_back({believed * t.pose_link.position, believed.linear() * t.pose_link.normal});
  const std::vector<int> touched = {4, 5};  // the centre taxel (nearest kContact) and one beside
  l.record_contact_offset(poses, touched, kTouchTime,
                          SkinTouch{kContact, Eigen::Vector3d::UnitZ()});
  ASSERT_EQ(l.contact_count(4), 1u);
  EXPECT_NEAR(l.contact_offset(4).value(), true_offset(poses[4]), 1e-3);
}

TEST(PpsTrueOffsets, APathAndAStraightBackOffAgree) {
  // The fingertip form (recorded path) equals the object form (back along the velocity) on a
  // straight path.
  somasim::SkinTaxels skin;
  skin.parts.push_back({"patch",
                        "link",
                        {7},
                        {Eigen::Vector3d::Zero()},
                        {Eigen::Vector3d::UnitZ()},
                        {Eigen::Vector3d::Zero()},
                        {Eigen::Vector3d::UnitZ()}});
  somasim::SkinTaxels believed = skin;
  believed.parts[0].positions[0] = Eigen::Vector3d(0.01, 0, -0.015);
  somasim::ContactEvent event;
  event.body_part = "patch";
  event.touched_taxels = {7};
  event.contact_point_link = kContact;
  std::vector<PathSample> path;
  for (int i = 0; i <= 100; ++i) {
    const double t = kTouchTime - 2.0 + 0.02 * i;
    path.push_back({t, object_at(t), object_at(t)});
  }
  TrueOffsets on_path, straight;
  on_path.sync_layout(skin);
  straight.sync_layout(skin);
  EXPECT_EQ(on_path.add_event_on_path(event, skin, believed, path, kOffsetClearance), 1);
  EXPECT_EQ(straight.add_event(event, skin, believed, object_at(kTouchTime), object_at(kTouchTime),
                               kOffsetClearance),
            1);
  somasim::TaxelValues a, b;
  on_path.write(a);
  straight.write(b);
  EXPECT_NEAR(a.values[0], b.values[0], 1e-9);
  EXPECT_NEAR(a.values[0],
              true_offset({Eigen::Vector3d(0.01, 0, -0.015), Eigen::Vector3d::UnitZ()}), 1e-9);
}
