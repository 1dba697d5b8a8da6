// object_thrower's `view`: each presentation checked against the robot's eyes (report), or
// drawn again until both eyes can see it coming (require); checked here against camera_sight
// on the taxels of the real left forearm, the head turned toward it or away from it.
#include <cmath>

#include "object_thrower_test_support.hpp"
#include "somasim/robot/camera_view.hpp"

using namespace object_thrower_test;
using somasim::LinkPoses;
using somasim::ObjectShape;
using somasim::Presentation;
using somasim::PresentationSight;

namespace {

// The arms raised in front; the head turned to the left forearm (or away from it, yaw -55 deg).
struct ForearmScene {
  std::shared_ptr<const somasim::robot::RobotModel> model =
      somasim::robot::load_robot_model_shared(kRobot);
  somasim::robot::RobotData data{*model};
  SkinPart part = forearm();

  explicit ForearmScene(double neck_yaw_deg) {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(model->num_dofs());
    const std::pair<const char*, double> posture[] = {
        {"l_shoulder_pitch", -60},  {"l_shoulder_roll", 40},
        {"l_shoulder_yaw", 45},     {"l_elbow", 55},
        {"l_wrist_prosup", -45},    {"neck_pitch", -40},
        {"neck_yaw", neck_yaw_deg}, {"eyes_tilt", -25}};
    for (const auto& [joint, deg] : posture) q[model->dof_index(joint)] = deg * M_PI / 180;
    somasim::robot::forward_kinematics(*model, data, q);
    const Eigen::Isometry3d link = data.link_poses[std::size_t(model->link_index("l_forearm"))];
    // Three taxels round the forearm: one faces the eyes, the others its sides.
    part = forearm_ring(link, {0.0, 120.0, 240.0});
  }

  // Whether both eyes see the object's centre at `point` (in the image, not behind a link).
  bool both_eyes_see(const Eigen::Vector3d& point) const {
    for (const auto& camera : model->cameras())
      if (somasim::robot::camera_sight(*model, data.link_poses, camera, point, 10.0) !=
          somasim::robot::Sight::kSeen)
        return false;
    return true;
  }
};

struct Shown {
  ObjectSpawn spawn;
  PresentationSight sight;
};

// Every presentation of a run of `params`, with the sight the thrower gave it.
std::vector<Shown> presentations(const ForearmScene& scene, const std::string& params) {
  Harness h(thrower(params, "link_poses: harness.poses"));
  feed_world(h);
  h.input<SkinTaxels>("taxels").parts = {scene.part};
  h.input<LinkPoses>("poses").poses = scene.data.link_poses;
  std::vector<Shown> out;
  std::uint64_t last = 0;
  while (h.step())
    for (const auto& s : h.output<ObjectSpawns>("t.spawns").recent)
      if (s.id > last) {
        last = s.id;
        out.push_back({s, h.output<Presentation>("t.presentation").sight});
      }
  h.finish();
  EXPECT_EQ(h.metric("t", "presentations_out_of_view"),
            std::count_if(out.begin(), out.end(),
                          [](const Shown& s) { return s.sight == PresentationSight::kOutOfView; }));
  return out;
}

constexpr const char* kParams =
    "approaches: 40, pause: 0, size: 0.02, shapes: sphere, cone_deg: 45, distance_min: 0.15, "
    "distance_max: 0.2, speed_min: 0.5, speed_max: 0.5";

}  // namespace

TEST(ObjectThrowerView, EachPresentationIsLabelledWithWhatTheEyesSee) {
  const ForearmScene scene(25.0);
  const auto shown = presentations(scene, kParams);
  ASSERT_EQ(shown.size(), 40u);
  int out = 0;
  for (const auto& s : shown) {
    // The start point decides most cases; a label of in_view needs it seen by both eyes.
    if (s.sight == PresentationSight::kInView) {
      EXPECT_TRUE(scene.both_eyes_see(s.spawn.pose.translation()));
    }
    out += s.sight == PresentationSight::kOutOfView;
    EXPECT_NE(s.sight, PresentationSight::kNotChecked);
  }
  EXPECT_GT(out, 3);   // the taxels on the far sides are approached from behind the arm
  EXPECT_LT(out, 37);  // the taxel facing the eyes is approached in view
}

TEST(ObjectThrowerView, RequiredViewPresentsOnlyWhatBothEyesSeeComing) {
  const ForearmScene scene(25.0);
  const auto shown = presentations(scene, std::string(kParams) + ", view: require");
  ASSERT_EQ(shown.size(), 40u);
  for (const auto& s : shown) {
    EXPECT_EQ(s.sight, PresentationSight::kInView);
    // Seen at the start and half way (the approach is checked until 5 cm from the skin).
    const Eigen::Vector3d start = s.spawn.pose.translation();
    EXPECT_TRUE(scene.both_eyes_see(start)) << start.transpose();
    const double travel = s.spawn.remove_after_s - 0.1;
    EXPECT_TRUE(scene.both_eyes_see(start + 0.5 * travel * s.spawn.linear_velocity));
  }
}

TEST(ObjectThrowerView, ForearmOutOfSightStopsTheRunSayingWhy) {
  const ForearmScene scene(-55.0);  // the head turned away from the left arm
  std::string msg;
  try {
    presentations(scene, std::string(kParams) + ", view: require, wait_for_clear_path: 0");
  } catch (const somasim::RunError& e) {
    msg = e.what();
  }
  EXPECT_NE(msg.find("seen coming by the cameras (view: require)"), std::string::npos) << msg;
  // Which eye, why and where on the path (the eyes look away: the forearm is behind them).
  EXPECT_NE(msg.find("the last 'left_eye': behind the camera"), std::string::npos) << msg;
  EXPECT_NE(msg.find("m from the end of the path"), std::string::npos) << msg;
}

TEST(ObjectThrowerView, CamerasAreNamedOnceAndMustExist) {
  EXPECT_NE(error_of(thrower("view_cameras: left_ey", "link_poses: harness.poses"))
                .find("unknown camera 'left_ey' (did you mean 'left_eye'?)"),
            std::string::npos);
  EXPECT_NE(error_of(thrower("view_cameras: left_eye left_eye", "link_poses: harness.poses"))
                .find("camera 'left_eye' is named twice"),
            std::string::npos);
  EXPECT_NE(error_of(thrower("view: require")).find("needs the robot's link poses"),
            std::string::npos);
}
