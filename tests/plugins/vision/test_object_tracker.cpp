// The `object_tracker` plugin through the public harness: its bad-input errors (a camera not in
// the robot model, images of another size than the camera's calibration).
#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/render/ports.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/testing/harness.hpp"

using somasim::Image;
using somasim::JointState;
using somasim::testing::Harness;

namespace {

const std::string kRobot = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml";

std::string graph(const std::string& params = "") {
  return "seed: 1\nbase_rate_hz: 20\nrobots: {icub: " + kRobot +
         "}\nnodes:\n  track:\n    plugin: object_tracker\n    params: {" + params +
         "}\n    inputs: {left_eye_rgb: harness.left, right_eye_rgb: harness.right, "
         "joint_state: harness.q}\n";
}

}  // namespace

TEST(ObjectTracker, CameraNotInTheRobotModelIsAClearError) {
  try {
    Harness h(graph("cameras: [left_eye, nose]"));
    FAIL() << "no error";
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "<inline>:7:23: node 'track', key 'params.cameras': camera 'nose' is not in robot "
                 "'icub_v1' (cameras: left_eye, right_eye)");
  }
}

TEST(ObjectTracker, ImagesOfAnotherSizeThanTheCalibrationAreARunError) {
  Harness h(graph());
  const auto model = somasim::robot::load_robot_model_shared(kRobot);
  h.input<JointState>("q").position = Eigen::VectorXd::Zero(model->num_dofs());
  for (const char* eye : {"left", "right"}) {
    Image& image = h.input<Image>(eye);
    image.data = cv::Mat(480, 640, CV_8UC3, cv::Scalar(0, 0, 0));
    image.encoding = somasim::ImageEncoding::kRgb8;
    image.camera = std::string(eye) + "_eye";
    image.frame = 1;
  }
  try {
    h.step(1);
    FAIL() << "no error";
  } catch (const somasim::RunError& e) {
    EXPECT_STREQ(e.what(),
                 "input 'left_eye_rgb': the image is 640 × 480 px, but camera 'left_eye' of "
                 "robot 'icub_v1' is calibrated for 320 × 240 px (wire images of that camera at "
                 "its resolution)");
  }
}
