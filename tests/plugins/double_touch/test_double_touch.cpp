// double_touch through the harness, with a perfect-servo stand-in world (the commanded posture is
// the true posture) and the left-forearm skin posed by forward kinematics: the touch geometry,
// the approach speed, the perceived stimulus (believed kinematics + noise), true_offsets and
// parameter errors.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kinematic_world.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/pps/stimulus.hpp"
#include "somasim/pps/true_offsets.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/skin/skin_layout.hpp"
#include "somasim/testing/harness.hpp"

using somasim::ContactEvent;
using somasim::ContactEvents;
using somasim::JointCommand;
using somasim::JointState;
using somasim::SkinPart;
using somasim::SkinTaxels;
using somasim::TaxelValues;
using somasim::pps::Stimulus;
using somasim::testing::Harness;
using somasim::testing::icub_path;
using somasim::testing::KinematicWorld;

namespace {

const char* kHome =
    "l_shoulder_pitch: -60, l_shoulder_roll: 30, l_shoulder_yaw: 30, l_elbow: 55, "
    "l_wrist_prosup: -45, r_shoulder_pitch: -45, r_shoulder_roll: 30, r_shoulder_yaw: 30, "
    "r_elbow: 70";
constexpr double kRadius = 0.0065;

std::string graph(const std::string& params, bool believed = false) {
  return "base_rate_hz: 100\nrobots: {icub: " + icub_path() +
         "}\nnodes:\n  t: {plugin: double_touch, params: {robot: icub" +
         (params.empty() ? "" : ", " + params) +
         "}, inputs: {state: harness.state, taxels: harness.taxels, contacts: harness.contacts" +
         (believed ? ", believed_state: harness.believed, believed_taxels: harness.btaxels" : "") +
         "}}\n";
}

// The generated left-forearm skin (virtual taxels), posed by forward kinematics at q.
struct Skin {
  explicit Skin(const somasim::robot::RobotModel& m) : model(m), data(m) {
    for (const auto& p : m.skin_patches())
      if (p.body_part == "left_forearm") layout = somasim::skin::generate_layout(p);
  }
  SkinTaxels pose(const Eigen::VectorXd& q, double shift_along_normal = 0.0) {
    somasim::robot::forward_kinematics(model, data, q);
    const Eigen::Isometry3d t = data.link_poses[static_cast<std::size_t>(layout.link)];
    SkinPart p;
    p.name = "left_forearm";
    p.link = "l_forearm";
    for (const auto& v : layout.virtual_taxels) {
      const auto c = static_cast<std::size_t>(v.centre);
      p.taxel_ids.push_back(v.id);
      p.positions_link.push_back(layout.positions[c]);
      p.normals_link.push_back(layout.normals[c]);
      const Eigen::Vector3d n = t.linear() * layout.normals[c];
      p.positions.push_back(t * layout.positions[c] + shift_along_normal * n);
      p.normals.push_back(n);
    }
    return SkinTaxels{{p}};
  }
  const somasim::robot::RobotModel& model;
  somasim::robot::RobotData data;
  somasim::skin::SkinLayout layout;
};

// Fingertip (frame origin) and finger axis (r_hand x) in the root frame at q.
std::pair<Eigen::Vector3d, Eigen::Vector3d> finger(const somasim::robot::RobotModel& m,
                                                   const Eigen::VectorXd& q) {
  somasim::robot::RobotData d(m);
  somasim::robot::forward_kinematics(m, d, q);
  const Eigen::Isometry3d tip = somasim::robot::frame_pose(d, m.frame_ref("r_index_tip"));
  return {tip.translation(), tip.linear().col(0)};
}

struct Tick {
  double t = 0;
  Eigen::VectorXd q;  // true posture when the node ran
  Stimulus stimulus, truth;
};

// Runs the graph to its end with the stand-in world; `believed_offset` is added to the true
// joint values for the believed_state input (when wired).
std::vector<Tick> run(Harness& h, bool believed = false,
                      const Eigen::VectorXd& believed_offset = {}, double taxel_shift = 0.0) {
  KinematicWorld w(0.01);
  w.state.position = somasim::robot::parse_posture_deg(*w.model, kHome);
  Skin skin(*w.model);
  std::vector<Tick> ticks;
  for (int i = 0; i < 20000; ++i) {
    h.input<JointState>("state") = w.state;
    h.input<SkinTaxels>("taxels") = skin.pose(w.state.position);
    if (believed) {
      JointState b = w.state;
      b.position += believed_offset;
      h.input<JointState>("believed") = b;
      h.input<SkinTaxels>("btaxels") = skin.pose(w.state.position, taxel_shift);
    }
    if (!h.step()) break;
    ticks.push_back({h.time_s(), w.state.position, h.output<Stimulus>("t.stimulus"),
                     h.output<Stimulus>("t.truth")});
    w.apply(h.output<JointCommand>("t.command"));
  }
  return ticks;
}

std::string error_of(const std::string& yaml) {
  try {
    Harness h(yaml);
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(DoubleTouch, FingertipPressesTheChosenTaxelsAlongTheirNormals) {
  Harness h(graph(
      "touches: 2, taxels: '23 11', position_jitter: 0, normal_jitter_deg: 0, move_duration: 0.5, "
      "hold: 0.2, press_depth: 0.003, start_distance: 0.2"));
  const auto ticks = run(h);
  EXPECT_EQ(h.finish(), "");
  EXPECT_EQ(h.metric("t", "touches"), 2);
  EXPECT_EQ(h.metric("t", "ik_failures"), 0);
  const auto per_touch = h.metric("t", "per_touch");
  ASSERT_EQ(per_touch.size(), 2u);
  EXPECT_EQ(per_touch[0]["taxel"], 23);
  EXPECT_EQ(per_touch[1]["taxel"], 11);
  // The stand-in world has no skin: no touch reached it.
  EXPECT_EQ(h.metric("t", "touches_reached_skin"), 0);

  const auto model = somasim::robot::load_robot_model_shared(icub_path());
  Skin skin(*model);
  for (int k = 0; k < 2; ++k) {
    const int id = per_touch[static_cast<std::size_t>(k)]["taxel"];
    // The tick nearest to the pressed target, and its finger axis.
    double best = 1e9, tilt = 0;
    for (const auto& tick : ticks) {
      const SkinTaxels s = skin.pose(tick.q);
      const Eigen::Vector3d x = s.parts[0].positions[static_cast<std::size_t>(id)];
      const Eigen::Vector3d n = s.parts[0].normals[static_cast<std::size_t>(id)];
      const auto [tip, axis] = finger(*model, tick.q);
      const double e = (tip - (x - 0.003 * n)).norm();
      if (e < best) {
        best = e;
        tilt = std::acos(std::clamp(axis.dot(-n), -1.0, 1.0));
      }
    }
    EXPECT_LT(best, 6e-4) << "touch " << k;
    EXPECT_NEAR(tilt * 180.0 / M_PI, 25.0, 2.0) << "touch " << k;  // finger_tilt
    EXPECT_LT(per_touch[static_cast<std::size_t>(k)]["final_error_m"].get<double>(), 6e-4);
  }
}

TEST(DoubleTouch, ApproachesAtASpeedInRangeAlongTheNormal) {
  Harness h(graph(
      "touches: 3, taxels: '19', position_jitter: 0, normal_jitter_deg: 0, move_duration: 0.5, "
      "hold: 0.1, speed_min: 0.08, speed_max: 0.12"));
  const auto ticks = run(h);
  EXPECT_EQ(h.finish(), "");
  const auto model = somasim::robot::load_robot_model_shared(icub_path());
  Skin skin(*model);
  const auto per_touch = h.metric("t", "per_touch");
  ASSERT_EQ(per_touch.size(), 3u);
  // Split the present stimulus into the three approaches (+ holds).
  std::size_t i = 0;
  for (int k = 0; k < 3; ++k) {
    const double v = per_touch[static_cast<std::size_t>(k)]["speed_m_s"];
    EXPECT_GE(v, 0.08);
    EXPECT_LE(v, 0.12);
    while (i < ticks.size() && !ticks[i].stimulus.present) ++i;
    ASSERT_LT(i, ticks.size());
    std::vector<Tick> seg;
    while (i < ticks.size() && ticks[i].stimulus.present) seg.push_back(ticks[i++]);
    // The fingertip relative to the taxel: the distance along the normal falls at v, the path
    // stays on the normal; the skin itself barely moves over the last 10 cm.
    double rate_min = 1e9, rate_max = 0, off_normal = 0, skin_speed_near = 0, joint_rate = 0;
    int moving = 0;
    for (std::size_t j = 2; j < seg.size(); ++j) {  // from the second step of the approach
      const SkinTaxels s0 = skin.pose(seg[j - 1].q), s1 = skin.pose(seg[j].q);
      const auto [a, ax] = finger(*model, seg[j - 1].q);
      const auto [b, bx] = finger(*model, seg[j].q);
      const Eigen::Vector3d x0 = s0.parts[0].positions[19], x1 = s1.parts[0].positions[19];
      const Eigen::Vector3d n0 = s0.parts[0].normals[19], n1 = s1.parts[0].normals[19];
      const double d0 = (a - x0).dot(n0), d1 = (b - x1).dot(n1);
      const double rate = (d0 - d1) / 0.01;
      if (rate < 0.2 * v || d1 < -0.0025) continue;  // the hold, the last (partial) step
      ++moving;
      rate_min = std::min(rate_min, rate);
      rate_max = std::max(rate_max, rate);
      const Eigen::Vector3d rel = b - x1;
      off_normal = std::max(off_normal, (rel - rel.dot(n1) * n1).norm());
      if (d1 < 0.1) skin_speed_near = std::max(skin_speed_near, (x1 - x0).norm() / 0.01);
      // No posture jumps: joints move at most 25 rad per metre of approach (the planner's bound).
      joint_rate = std::max(joint_rate, (seg[j].q - seg[j - 1].q).cwiseAbs().maxCoeff() / 0.01);
    }
    EXPECT_GT(moving, static_cast<int>(0.19 / v / 0.01));  // ~0.2 m at v
    EXPECT_NEAR(rate_min, v, 0.03 * v) << "touch " << k;
    EXPECT_NEAR(rate_max, v, 0.03 * v) << "touch " << k;
    EXPECT_LT(skin_speed_near, 0.02) << "touch " << k;
    EXPECT_LT(joint_rate, 25.0 * v * 1.1) << "touch " << k;
    EXPECT_LT(off_normal, 0.002) << "touch " << k;
  }
}

TEST(DoubleTouch, StimulusIsTheBelievedFingertipPlusNoise) {
  const auto model = somasim::robot::load_robot_model_shared(icub_path());
  Eigen::VectorXd offset = Eigen::VectorXd::Zero(model->num_dofs());
  offset[model->dof_index("r_elbow")] = 5.0 * M_PI / 180.0;
  offset[model->dof_index("l_elbow")] = -3.0 * M_PI / 180.0;
  const auto centre = [&](const Eigen::VectorXd& q) {
    const auto [tip, axis] = finger(*model, q);
    return Eigen::Vector3d(tip - kRadius * axis);
  };
  {
    Harness h(graph("touches: 1, taxels: '23', move_duration: 0.5", true));
    const auto ticks = run(h, true, offset);
    EXPECT_EQ(h.finish(), "");
    int present = 0;
    for (std::size_t i = 1; i < ticks.size(); ++i) {
      if (!ticks[i].stimulus.present) continue;
      ++present;
      const Eigen::Vector3d believed = centre(ticks[i].q + offset);
      EXPECT_LT((ticks[i].stimulus.position - believed).norm(), 1e-12);
      EXPECT_LT((ticks[i].truth.position - centre(ticks[i].q)).norm(), 1e-12);
      EXPECT_GT((believed - centre(ticks[i].q)).norm(), 0.01);  // the injected error shows
      // Velocity: finite difference over the node period.
      const Eigen::Vector3d v = (believed - centre(ticks[i - 1].q + offset)) / 0.01;
      EXPECT_LT((ticks[i].stimulus.velocity - v).norm(), 1e-9);
      EXPECT_EQ(ticks[i].stimulus.radius, kRadius);
    }
    EXPECT_GT(present, 100);
  }
  {
    Harness h(graph("touches: 2, taxels: '23', move_duration: 0.5, position_noise: 0.002", true));
    const auto ticks = run(h, true, offset);
    EXPECT_EQ(h.finish(), "");
    double sum = 0, sum2 = 0;
    int n = 0;
    for (const auto& t : ticks) {
      if (!t.stimulus.present) continue;
      const Eigen::Vector3d r = t.stimulus.position - centre(t.q + offset);
      for (int k = 0; k < 3; ++k) {
        sum += r[k];
        sum2 += r[k] * r[k];
        ++n;
      }
      EXPECT_LT((t.truth.position - centre(t.q)).norm(), 1e-12);  // truth has no noise
    }
    ASSERT_GT(n, 300);
    EXPECT_NEAR(sum / n, 0.0, 0.0004);
    EXPECT_NEAR(std::sqrt(sum2 / n), 0.002, 0.0003);
  }
}

TEST(DoubleTouch, TrueOffsetsArePerceivedMinusTrueDAtTheEvents) {
  const auto model = somasim::robot::load_robot_model_shared(icub_path());
  Harness h(graph("touches: 1, taxels: '23', move_duration: 0.5, hold: 0.5", true));
  KinematicWorld w(0.01);
  w.state.position = somasim::robot::parse_posture_deg(*w.model, kHome);
  Skin skin(*w.model);
  Eigen::VectorXd offset = Eigen::VectorXd::Zero(model->num_dofs());
  offset[model->dof_index("r_wrist_pitch")] = -4.0 * M_PI / 180.0;
  bool sent = false;
  Stimulus perceived, truth;
  SkinTaxels believed_taxels, true_taxels;
  std::vector<somasim::pps::PathSample> path;  // the fingertip as the node sees it, per tick
  ContactEvent event;
  while (true) {
    {
      const auto [bt, ba] = finger(*model, w.state.position + offset);
      const auto [tt, ta] = finger(*model, w.state.position);
      path.push_back({h.time_s(),
                      Stimulus{bt - kRadius * ba, Eigen::Vector3d::Zero(), kRadius, true},
                      Stimulus{tt - kRadius * ta, Eigen::Vector3d::Zero(), kRadius, true}});
    }
    h.input<JointState>("state") = w.state;
    true_taxels = skin.pose(w.state.position);
    h.input<SkinTaxels>("taxels") = true_taxels;
    JointState b = w.state;
    b.position += offset;
    h.input<JointState>("believed") = b;
    believed_taxels = skin.pose(w.state.position, 0.01);  // believed 1 cm out along the normals
    h.input<SkinTaxels>("btaxels") = believed_taxels;
    // At the hold (the stimulus present and still), the skin reports a touch of taxels 23, 22.
    const bool holding = h.time_s() > 0 && h.output<Stimulus>("t.stimulus").present &&
                         h.output<Stimulus>("t.stimulus").velocity.norm() < 1e-9;
    if (holding && !sent) {
      ContactEvent e;
      e.id = 1;
      e.time_s = h.time_s();
      e.body_part = "left_forearm";
      e.touched_taxels = {23, 22};
      event = e;
      h.input<ContactEvents>("contacts").recent = {e};
      sent = true;
    }
    if (!h.step()) break;
    if (sent && perceived.radius == 0) {
      // The node's offsets: on its recorded path, where the true tip was kOffsetClearance
      // outside each touched taxel (the event has no centre of pressure: both are credited).
      perceived = path.back().perceived;
      const auto& out = h.output<TaxelValues>("t.true_offsets");
      ASSERT_EQ(out.labels.size(), 32u);
      EXPECT_EQ(out.labels[23], "left_forearm/23");
      somasim::pps::TrueOffsets expected;
      expected.sync_layout(true_taxels);
      ASSERT_EQ(expected.add_event_on_path(event, true_taxels, believed_taxels, path,
                                           somasim::pps::kOffsetClearance),
                2);
      TaxelValues want;
      expected.write(want);
      for (int id : {22, 23}) {
        const auto k = static_cast<std::size_t>(id);
        EXPECT_NEAR(out.values[k], want.values[k], 1e-12) << id;
        EXPECT_LT(std::abs(out.values[k]), 0.03) << id;  // a 1 cm-class error
      }
      for (std::size_t k = 0; k < out.values.size(); ++k) {
        if (k != 22 && k != 23) {
          EXPECT_TRUE(std::isnan(out.values[k])) << k;
        }
      }
    }
    w.apply(h.output<JointCommand>("t.command"));
  }
  EXPECT_TRUE(sent);
  EXPECT_EQ(h.finish(), "");
  EXPECT_EQ(h.metric("t", "touches_reached_skin"), 1);
  EXPECT_EQ(h.metric("t", "touches_on_aimed_taxel"), 1);  // the event named taxel 23
  EXPECT_EQ(h.metric("t", "events_on_part"), 1);
  EXPECT_EQ(h.metric("t", "true_offset_samples"), 2);
}

TEST(DoubleTouch, SameSeedSameTouches) {
  const auto metrics = [] {
    Harness h(graph("touches: 3, move_duration: 0.5"));
    run(h);
    h.finish();
    return h.metric("t", "per_touch").dump();
  };
  const std::string a = metrics();
  EXPECT_EQ(a, metrics());
  EXPECT_NE(a.find("\"taxel\""), std::string::npos);
}

TEST(DoubleTouch, ParameterErrors) {
  const std::string where = "node 't', key 'params.";
  EXPECT_NE(error_of(graph("body_part: left_forarm"))
                .find(where + "body_part': unknown skin part 'left_forarm' (did you mean "
                              "'left_forearm'?); the robot's skin parts: left_forearm, right_palm"),
            std::string::npos)
      << error_of(graph("body_part: left_forarm"));
  EXPECT_NE(
      error_of(graph("effector: r_index_tp"))
          .find(where + "effector': robot 'icub_v1': unknown frame or link 'r_index_tp' (did you "
                        "mean 'r_index_tip'?)"),
      std::string::npos)
      << error_of(graph("effector: r_index_tp"));
  // The finger on the touched part itself.
  EXPECT_NE(error_of(graph("body_part: right_palm"))
                .find(where + "effector': touch IK: no joint moves link 'r_hand' or link 'r_hand' "
                              "without moving both (nothing to solve)"),
            std::string::npos)
      << error_of(graph("body_part: right_palm"));
  EXPECT_NE(error_of(graph("speed_min: 0.2, speed_max: 0.1"))
                .find(where + "speed_max': must not be less than speed_min"),
            std::string::npos);
  EXPECT_NE(
      error_of(graph("effector_axis: [0, 0, 0]")).find(where + "effector_axis': must not be zero"),
      std::string::npos);
  EXPECT_NE(error_of(graph("taxels: '3 x'"))
                .find(where + "taxels': expected taxel ids (integers >= 0), got 'x'"),
            std::string::npos);
  EXPECT_NE(error_of(graph("home_posture_deg: 'l_elbow: 300'"))
                .find(where + "home_posture_deg': joint 'l_elbow': 300 deg is outside the limits "
                              "[5.5, 106]"),
            std::string::npos)
      << error_of(graph("home_posture_deg: 'l_elbow: 300'"));
  // Out of range (checked by the parameter schema).
  EXPECT_NE(error_of(graph("speed_max: 5")).find("speed_max"), std::string::npos);
}

TEST(DoubleTouch, RunErrors) {
  const auto run_error = [](Harness& h, bool feed) {
    try {
      if (feed)
        run(h);
      else
        h.step();
    } catch (const somasim::RunError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  {
    Harness h(graph("taxels: '77'"));
    EXPECT_EQ(run_error(h, true), "taxel 77 is not a taxel of 'left_forearm' (32 taxels)");
  }
  {
    Harness h(graph(""));
    h.input<JointState>("state").position = Eigen::VectorXd::Zero(3);
    EXPECT_EQ(run_error(h, false),
              "'state' has 3 joint values, expected 23 (is it wired to the world's joint_state?)");
  }
  {
    Harness h(graph("taxels: '0'"));  // by the wrist: the hands would collide
    EXPECT_EQ(run_error(h, true),
              "taxel 0 of 'left_forearm' cannot be touched from the home posture (20 attempts; "
              "see the log)");
  }
  {
    Harness h(graph("start_distance: 1.0"));  // no arm reaches 1 m out along a normal
    EXPECT_EQ(run_error(h, true),
              "no taxel of 'left_forearm' can be touched from the home posture (see the log at "
              "debug level)");
  }
  {
    // An event on a part the believed taxels lack.
    Harness h(graph("taxels: '23'", true));
    KinematicWorld w(0.01);
    w.state.position = somasim::robot::parse_posture_deg(*w.model, kHome);
    Skin skin(*w.model);
    h.input<JointState>("state") = w.state;
    h.input<JointState>("believed") = w.state;
    h.input<SkinTaxels>("taxels") = skin.pose(w.state.position);
    h.input<SkinTaxels>("btaxels") = SkinTaxels{};
    ContactEvent e;
    e.id = 1;
    e.body_part = "left_forearm";
    e.touched_taxels = {23};
    h.input<ContactEvents>("contacts").recent = {e};
    EXPECT_EQ(run_error(h, false),
              "input 'believed_taxels' has no skin part 'left_forearm' (wire "
              "believed_kinematics.taxels)");
  }
  {
    Harness h(graph(""));
    KinematicWorld w(0.01);
    h.input<JointState>("state") = w.state;  // no skin yet
    EXPECT_EQ(run_error(h, false),
              "skin part 'left_forearm' (with link-frame taxel poses) is not in the 'taxels' "
              "input (is the skin node wired?)");
  }
}
