// The MJCF exporter: every link a body, every dof a joint and a servo, the exempt pairs excluded;
// with MuJoCo present, the loaded model's bodies follow somasim's links at any posture (shipped
// and generated robots) and its servos hold a posture.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>

#include <fmt/format.h>

#include "robot_test_support.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/mjcf_export.hpp"
#include "somasim/robot/self_collision.hpp"

#ifdef SOMASIM_HAVE_MUJOCO
#include <mujoco/mujoco.h>
#endif

namespace somasim::robot {
namespace {

namespace fs = std::filesystem;

std::size_t count(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  return static_cast<std::size_t>(
      std::distance(std::sregex_iterator(text.begin(), text.end(), re), std::sregex_iterator()));
}

std::vector<RobotModel> robots_under_test(std::mt19937& rng) {
  std::vector<RobotModel> robots;
  for (const char* variant : {"icub_v1", "icub_v2", "icub_v1_from_urdf"})
    robots.push_back(test::load_icub(variant));
  for (int trial = 0; trial < 20; ++trial) robots.push_back(test::random_tree(rng, 2 + trial % 9));
  return robots;
}

TEST(MjcfExport, EveryLinkIsABodyEveryDofAJointAndAServoEveryExemptPairExcluded) {
  std::mt19937 rng(11);
  for (const RobotModel& model : robots_under_test(rng)) {
    SCOPED_TRACE(model.name());
    const std::string mjcf = to_mjcf(model);
    EXPECT_EQ(count(mjcf, "<body "), static_cast<std::size_t>(model.num_links()));
    EXPECT_EQ(count(mjcf, "<joint "), static_cast<std::size_t>(model.num_dofs()));
    EXPECT_EQ(count(mjcf, "<general "), static_cast<std::size_t>(model.num_dofs()));
    std::size_t shapes = 0, exempt_pairs = 0;
    const auto exempt = collision_exempt_links(model);
    for (int a = 0; a < model.num_links(); ++a) {
      shapes += model.link(a).collision.size();
      for (int b = a + 1; b < model.num_links(); ++b)
        exempt_pairs +=
            exempt[a][b] && !model.link(a).collision.empty() && !model.link(b).collision.empty();
    }
    EXPECT_EQ(count(mjcf, "<geom type="), shapes);
    EXPECT_EQ(count(mjcf, "<exclude "), exempt_pairs);
    MjcfOptions no_servos;
    no_servos.servos = false;
    EXPECT_EQ(count(to_mjcf(model, no_servos), "<general "), 0U);
  }
}

TEST(MjcfExport, ServoGainsAreCriticallyDampedAtTheBandwidth) {
  const RobotModel model = test::load_icub();
  MjcfOptions options;
  options.servo_bandwidth = 25.0;
  const ServoGains gains = mjcf_servo_gains(model, options);
  for (int d = 0; d < model.num_dofs(); ++d) {
    ASSERT_GT(gains.kp[d], 0.0);
    EXPECT_NEAR(gains.kd[d] * gains.kd[d], 4.0 * gains.kp[d] * gains.kp[d] / (25.0 * 25.0),
                1e-9 * gains.kp[d] * gains.kp[d]);
  }
  // The shoulder carries the whole arm: more inertia than the elbow, which carries the forearm.
  EXPECT_GT(gains.kp[model.dof_index("l_shoulder_pitch")], gains.kp[model.dof_index("l_elbow")]);
}

#ifdef SOMASIM_HAVE_MUJOCO

class LoadedModel {
 public:
  explicit LoadedModel(const std::string& mjcf) {
    path_ = fs::temp_directory_path() / fmt::format("somasim_mjcf_{}.xml", ::getpid());
    std::ofstream(path_) << mjcf;
    char error[1000] = "";
    model_ = mj_loadXML(path_.c_str(), nullptr, error, sizeof error);
    fs::remove(path_);
    if (!model_) throw std::runtime_error(error);
    data_ = mj_makeData(model_);
  }
  ~LoadedModel() {
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }
  LoadedModel(const LoadedModel&) = delete;
  LoadedModel& operator=(const LoadedModel&) = delete;
  mjModel* m() const { return model_; }
  mjData* d() const { return data_; }

 private:
  fs::path path_;
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
};

TEST(MjcfExportMujoco, BodiesFollowTheLinksAtEveryPosture) {
  std::mt19937 rng(5);
  for (const RobotModel& model : robots_under_test(rng)) {
    SCOPED_TRACE(model.name());
    const LoadedModel mj(to_mjcf(model));
    ASSERT_EQ(mj.m()->nq, model.num_dofs());
    ASSERT_EQ(mj.m()->nbody, model.num_links() + 1);  // + the world
    const std::vector<int> dofs = mjcf_joint_dofs(model);
    ASSERT_EQ(static_cast<int>(dofs.size()), model.num_dofs());
    for (int k = 0; k < model.num_dofs(); ++k) {
      const int d = dofs[static_cast<std::size_t>(k)];
      EXPECT_EQ(mj_id2name(mj.m(), mjOBJ_JOINT, k), model.joint(model.dof_joint(d)).name);
      EXPECT_EQ(mj.m()->jnt_qposadr[k], k);
      EXPECT_EQ(mj.m()->actuator_trnid[2 * d], k);  // ctrl[d] drives dof d
      if (mj.m()->jnt_limited[k]) {
        EXPECT_DOUBLE_EQ(mj.m()->jnt_range[2 * k], model.lower_limits()[d]);
        EXPECT_DOUBLE_EQ(mj.m()->jnt_range[2 * k + 1], model.upper_limits()[d]);
      }
    }
    RobotData data(model);
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::VectorXd q = test::random_posture(model, rng);
      forward_kinematics(model, data, q);
      for (int k = 0; k < model.num_dofs(); ++k)
        mj.d()->qpos[k] = q[dofs[static_cast<std::size_t>(k)]];
      mj_kinematics(mj.m(), mj.d());
      for (int l = 0; l < model.num_links(); ++l) {
        const int b = mj_name2id(mj.m(), mjOBJ_BODY, model.link(l).name.c_str());
        ASSERT_GE(b, 1) << model.link(l).name;
        const Eigen::Map<const Eigen::Vector3d> p(mj.d()->xpos + 3 * b);
        const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> r(mj.d()->xmat +
                                                                               9 * b);
        EXPECT_LT((p - data.link_poses[l].translation()).norm(), 1e-9) << model.link(l).name;
        EXPECT_LT((r - data.link_poses[l].linear()).cwiseAbs().maxCoeff(), 1e-9)
            << model.link(l).name;
      }
    }
    // Mass: the model's, plus a frame link's for each moving group without any.
    double mass = 0.0;
    for (int b = 1; b < mj.m()->nbody; ++b) mass += mj.m()->body_mass[b];
    EXPECT_GE(mass, model.total_mass() - 1e-9);
    EXPECT_LE(mass, model.total_mass() + 0.02 * model.num_dofs() + 1e-9);
    EXPECT_EQ(mj.m()->nexclude, static_cast<int>(count(to_mjcf(model), "<exclude ")));
  }
}

TEST(MjcfExportMujoco, ServosHoldAPostureUnderGravityAndFollowAWave) {
  const RobotModel model = test::load_icub();
  const Eigen::VectorXd q0 = parse_posture_deg(
      model,
      "l_shoulder_pitch: -40, l_shoulder_roll: 40, l_elbow: 60, r_shoulder_pitch: -40, "
      "r_shoulder_roll: 40, r_elbow: 60");
  MjcfOptions options;
  options.posture = q0;
  const ServoGains gains = mjcf_servo_gains(model, options);
  const LoadedModel mj(to_mjcf(model, options));
  const std::vector<int> dofs = mjcf_joint_dofs(model);
  for (int k = 0; k < model.num_dofs(); ++k) ASSERT_EQ(dofs[static_cast<std::size_t>(k)], k);
  for (int d = 0; d < model.num_dofs(); ++d) mj.d()->qpos[d] = q0[d];
  const int elbow = model.dof_index("r_elbow");
  double worst = 0.0;
  for (int step = 0; step < 2000; ++step) {
    const double t = step * 1e-3;
    Eigen::VectorXd target = q0, velocity = Eigen::VectorXd::Zero(model.num_dofs());
    target[elbow] += 0.25 * std::sin(3.0 * t);
    velocity[elbow] = 0.75 * std::cos(3.0 * t);
    mj_forward(mj.m(), mj.d());  // qfrc_bias: gravity and Coriolis, fed forward
    for (int d = 0; d < model.num_dofs(); ++d)
      mj.d()->ctrl[d] =
          target[d] + gains.kd[d] / gains.kp[d] * velocity[d] + mj.d()->qfrc_bias[d] / gains.kp[d];
    mj_step(mj.m(), mj.d());
    if (t >= 0.5)
      for (int d = 0; d < model.num_dofs(); ++d)
        worst = std::max(worst, std::abs(mj.d()->qpos[d] - target[d]));
  }
  EXPECT_LT(worst, 1.0 * M_PI / 180.0);
}

#endif

}  // namespace
}  // namespace somasim::robot
