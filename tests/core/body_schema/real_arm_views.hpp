#pragma once
// Test and benchmark support: the "real" iCub right arm (encoders plus the paper's offsets
// beta = [5, 4, 3, -2, 3, -7, 3] deg) rendered by the SceneRenderer on a white background in
// both eyes, as the body-schema filter's cameras would see it.
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "somasim/render/context.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_loader.hpp"

namespace somasim::body_schema::testing {

inline std::shared_ptr<const robot::RobotModel> icub() {
  static const auto m =
      robot::load_robot_model_shared(SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml");
  return m;
}

inline const std::vector<std::string>& arm_joints() {
  static const std::vector<std::string> j = {
      "r_shoulder_pitch", "r_shoulder_roll", "r_shoulder_yaw", "r_elbow",
      "r_wrist_prosup",   "r_wrist_pitch",   "r_wrist_yaw"};
  return j;
}

inline const Eigen::Matrix<double, 7, 1>& true_offsets_deg() {
  static const Eigen::Matrix<double, 7, 1> b =
      (Eigen::Matrix<double, 7, 1>() << 5, 4, 3, -2, 3, -7, 3).finished();
  return b;
}

inline std::vector<int> arm_dofs() {
  std::vector<int> dofs;
  for (const auto& j : arm_joints()) dofs.push_back(icub()->dof_index(j));
  return dofs;
}

/// Encoder readings with the right hand in front of the eyes (head straight).
inline Eigen::VectorXd hand_before_eyes() {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(icub()->num_dofs());
  const std::map<std::string, double> deg = {{"r_shoulder_pitch", -85}, {"r_shoulder_roll", 10},
                                             {"r_shoulder_yaw", 20},    {"r_elbow", 50},
                                             {"r_wrist_prosup", 10},    {"r_wrist_pitch", -10}};
  for (const auto& [j, d] : deg) q[icub()->dof_index(j)] = d * std::numbers::pi / 180.0;
  return q;
}

struct RealEyes {
  std::vector<render::Camera> cameras;
  std::vector<cv::Mat> rgb;  ///< CV_8UC3, R G B
};

/// The real arm (q + true offsets) seen by both eyes, rendered on this thread with `backend`.
inline RealEyes look(const Eigen::VectorXd& q,
                     render::RenderBackend backend = render::RenderBackend::kOsmesa) {
  const std::unique_ptr<render::RenderContext> context = render::make_render_context(backend);
  render::SceneRenderer renderer(context->gl());
  render::RobotScene scene(renderer, icub());
  robot::RobotData data(*icub());
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(icub()->num_dofs());
  const std::vector<int> dofs = arm_dofs();
  for (std::size_t j = 0; j < dofs.size(); ++j)
    beta[dofs[j]] = true_offsets_deg()[static_cast<Eigen::Index>(j)] * std::numbers::pi / 180.0;
  robot::forward_kinematics(*icub(), data, q, beta);
  RealEyes eyes;
  render::RenderOptions options;
  options.background = Eigen::Vector3f::Ones();
  for (const char* eye : {"left_eye", "right_eye"}) {
    const render::Camera cam = render::camera_for(*icub(), eye, data.link_poses);
    std::vector<render::DrawItem> items;
    const Eigen::Vector3d viewpoint = cam.pose_root.translation();
    scene.add_robot(data.link_poses, items, &viewpoint);
    eyes.cameras.push_back(cam);
    eyes.rgb.push_back(renderer.render(items, cam, options).rgb);
  }
  return eyes;
}

}  // namespace somasim::body_schema::testing
