// The gaze solve on the iCub: points in reach end on both optical axes; points out of reach
// leave joints at their limits (reported), never beyond them.
#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/units.hpp"
#include "somasim/vision/gaze.hpp"

namespace vision = somasim::vision;
namespace robot = somasim::robot;

namespace {

std::shared_ptr<const robot::RobotModel> icub() {
  static const auto m =
      robot::load_robot_model_shared(SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml");
  return m;
}

// A point given in the left eye's frame at q = 0 (x right, y down, z forward) [m].
Eigen::Vector3d ahead(const Eigen::Vector3d& in_left_eye) {
  robot::RobotData data(*icub());
  robot::forward_kinematics(*icub(), data, Eigen::VectorXd::Zero(icub()->num_dofs()));
  return somasim::render::camera_for(*icub(), "left_eye", data.link_poses).pose_root * in_left_eye;
}

}  // namespace

TEST(Gaze, PointsInReachEndOnBothOpticalAxes) {
  const vision::GazeSolver solver(icub());
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(icub()->num_dofs());
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0.034, 0, 0.5), Eigen::Vector3d(0.15, 0.1, 0.4),
        Eigen::Vector3d(-0.2, -0.1, 0.6), Eigen::Vector3d(0.03, 0.05, 0.25)}) {
    const vision::GazeSolution s = solver.solve(q0, ahead(p));
    EXPECT_LT(s.residual_rad, 1e-6) << p.transpose();
    EXPECT_TRUE(s.at_limit.empty()) << p.transpose();
    EXPECT_FALSE(s.behind);
    robot::RobotData data(*icub());
    robot::forward_kinematics(*icub(), data, s.q);
    for (const char* eye : {"left_eye", "right_eye"}) {
      const auto cam = somasim::render::camera_for(*icub(), eye, data.link_poses);
      const Eigen::Vector2d uv = *cam.project(ahead(p));
      EXPECT_LT((uv - Eigen::Vector2d(cam.intrinsics.cx, cam.intrinsics.cy)).norm(), 0.01)
          << eye << " " << p.transpose();
    }
    // Only the gaze joints move.
    for (int d = 0; d < icub()->num_dofs(); ++d)
      if (std::find(solver.dofs().begin(), solver.dofs().end(), d) == solver.dofs().end()) {
        EXPECT_EQ(s.q[d], 0.0);
      }
  }
}

TEST(Gaze, PointsOutOfReachAreClampedAndReported) {
  const vision::GazeSolver solver(icub());
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(icub()->num_dofs());
  // Far to the robot's left side (beyond neck yaw + eye pan) and high above.
  const vision::GazeSolution s = solver.solve(q0, ahead({-2.0, -1.5, 0.3}));
  EXPECT_GT(s.residual_rad, 0.1);
  EXPECT_FALSE(s.at_limit.empty());
  const Eigen::VectorXd& lo = icub()->lower_limits();
  const Eigen::VectorXd& hi = icub()->upper_limits();
  for (const int d : solver.dofs()) {
    EXPECT_GE(s.q[d], lo[d]);
    EXPECT_LE(s.q[d], hi[d]);
  }
}

TEST(Gaze, UnknownJointOrCameraIsAClearError) {
  vision::GazeOptions options;
  options.neck_joints = {"neck_pitch", "nek_yaw"};
  try {
    vision::GazeSolver solver(icub(), options);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "gaze: robot 'icub_v1': unknown joint 'nek_yaw' (did you mean 'neck_yaw'?)");
  }
  options = {};
  options.cameras = {"left_eye", "nose"};
  try {
    vision::GazeSolver solver(icub(), options);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "gaze: camera 'nose' is not in robot 'icub_v1' (cameras: left_eye, right_eye)");
  }
}
