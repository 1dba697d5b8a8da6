// double_touch's parameters and ports.
#include "double_touch.hpp"

#include "somasim/robot/experiment_robot.hpp"

namespace somasim::plugins {

namespace {

// A double-touch posture of the iCub: the left forearm in front of the body, turned (prosup)
// so that most of its skin faces the right hand, the right hand beside it (21 of the 32 forearm
// taxels of icub_v1 can then be touched).
const char* kDefaultHome =
    "l_shoulder_pitch: -60, l_shoulder_roll: 30, l_shoulder_yaw: 30, l_elbow: 55, "
    "l_wrist_prosup: -45, r_shoulder_pitch: -45, r_shoulder_roll: 30, r_shoulder_yaw: 30, "
    "r_elbow: 70";

}  // namespace

PluginSpec DoubleTouch::spec() {
  PluginSpec s("double_touch",
               "Self-touch for tactile-motor PPS learning: the right index fingertip touches "
               "taxels of the left forearm along their normals (both arms solved together), "
               "approaching from start_distance at speed_min..speed_max, again and again; the "
               "stimulus is the fingertip from the believed kinematics (proprioception) + noise.");
  robot::add_robot_param(s);
  s.add_string("body_part")
      .defaults(std::string("left_forearm"))
      .describe("the skin part touched (its link is moved by the other arm's joints)");
  s.add_string("effector")
      .defaults(std::string("r_index_tip"))
      .describe("the touching frame (its origin is the fingertip)");
  s.add_list("effector_axis")
      .size(3)
      .defaults(std::vector<double>{1, 0, 0})
      .describe("the finger's pointing direction in the effector frame (brought along -normal)");
  s.add_list("effector_side")
      .size(3)
      .defaults(std::vector<double>{0, 1, 0})
      .describe(
          "direction from the touching finger toward the other fingers (effector frame); they "
          "are kept across the limb (perpendicular to limb_axis) and lifted by finger_tilt_deg");
  s.add_list("limb_axis")
      .size(3)
      .defaults(std::vector<double>{0, 1, 0})
      .describe("the touched limb's long axis in its link frame; zero: the hand's roll is free");
  s.add_double("finger_tilt_deg")
      .unit_is("deg")
      .defaults(25.0)
      .range(0.0, 60.0)
      .describe(
          "the finger leans this far from -normal (across the limb) so that the longer "
          "neighbouring finger stays off the skin; the fingertip still moves along the normal");
  s.add_double("finger_radius")
      .unit_is("m")
      .defaults(0.0065)
      .range(0.0, 0.1)
      .describe("stimulus radius: the ball inscribed in the fingertip");
  s.add_string_list("taxels")
      .defaults(std::vector<std::string>{})
      .describe("taxel ids touched in turn; empty = random reachable taxels");
  s.add_int("touches")
      .defaults(std::int64_t{20})
      .range(1, 100000)
      .describe("touches; the arms then return home and the run stops");
  s.add_double("start_distance")
      .unit_is("m")
      .defaults(0.20)
      .range(0.01, 1.0)
      .describe("the approach starts this far from the skin along the normal");
  s.add_double("press_depth")
      .unit_is("m")
      .defaults(0.003)
      .range(0.0, 0.02)
      .describe("the approach ends this far below the taxel (a slight press)");
  s.add_double("align_distance")
      .unit_is("m")
      .defaults(0.03)
      .range(0.0, 1.0)
      .describe(
          "within this distance of the skin the finger keeps its orientation (axis, tilt, "
          "fingers across the limb); farther out it may lean, up to max_tilt_deg at "
          "start_distance");
  s.add_double("max_tilt_deg")
      .unit_is("deg")
      .defaults(60.0)
      .range(0.0, 90.0)
      .describe("largest lean of the finger from -normal at start_distance");
  s.add_double("approach_step")
      .unit_is("m")
      .defaults(0.01)
      .range(0.001, 0.1)
      .describe("spacing of the IK solutions along the approach (joint-space interpolation)");
  s.add_double("speed_min")
      .unit_is("m/s")
      .defaults(0.05)
      .range(0.001, 1.0)
      .describe("slowest approach speed of the fingertip");
  s.add_double("speed_max")
      .unit_is("m/s")
      .defaults(0.15)
      .range(0.001, 1.0)
      .describe("fastest approach speed (also the retreat speed)");
  s.add_double("position_jitter")
      .unit_is("m")
      .defaults(0.003)
      .range(0.0, 0.05)
      .describe("aimed point: Gaussian σ per tangential axis around the taxel");
  s.add_double("normal_jitter_deg")
      .unit_is("deg")
      .defaults(5.0)
      .range(0.0, 45.0)
      .describe("approach direction drawn within this angle of the taxel normal");
  s.add_string("home_posture_deg")
      .accepts_map_as_text()
      .defaults(std::string(kDefaultHome))
      .describe("'joint: value, ...' [deg]: posture regularisation and the final posture");
  s.add_double("move_duration")
      .unit_is("s")
      .defaults(2.0)
      .range(0.1, 60.0)
      .describe("joint-space (minimum-jerk) move to the start of each approach");
  s.add_double("hold").unit_is("s").defaults(0.3).range(0.0, 60.0).describe(
      "pause on the skin before retreating");
  s.add_double("clearance")
      .unit_is("m")
      .defaults(0.002)
      .range(-0.1, 0.2)
      .describe("smallest distance kept between the arms elsewhere (capsule bounds)");
  s.add_double("position_noise")
      .unit_is("m")
      .defaults(0.0)
      .range(0.0, 1.0)
      .describe("perceived fingertip position noise (Gaussian σ per axis)");
  s.add_double("velocity_noise")
      .unit_is("m/s")
      .defaults(0.0)
      .range(0.0, 10.0)
      .describe("perceived fingertip velocity noise (Gaussian σ per axis)");
  s.add_string("perception")
      .defaults(std::string("proprioception"))
      .one_of({"proprioception", "vision"})
      .describe(
          "how the robot perceives its fingertip, for `stimulus` and `true_offsets`: "
          "proprioception = the fingertip ball of the believed arm kinematics; vision = the "
          "marker seen by ideal eyes: a ball of marker_radius centred on the TRUE effector "
          "origin (the arm's joint offsets do not enter; wire a marker tracker's stimulus to "
          "the learner and compare with these offsets)");
  s.add_double("marker_radius")
      .unit_is("m")
      .defaults(0.007)
      .range(0.0, 0.1)
      .describe("radius of the fingertip marker (perception: vision)");
  s.input<JointState>("state", "true joint values (world.joint_state)");
  s.input<SkinTaxels>("taxels", "skin taxels posed by the true kinematics (skin.taxels)");
  s.input<ContactEvents>("contacts", "skin contact events (skin.contacts)", /*optional=*/true);
  s.input<JointState>("believed_state", "joint values the robot believes (default: the true ones)",
                      /*optional=*/true);
  s.input<SkinTaxels>("believed_taxels",
                      "taxels posed by the believed kinematics (the learner's; for true_offsets)",
                      /*optional=*/true);
  s.output<JointCommand>("command", "position commands (with velocity feed-forward), both arms");
  s.output<pps::Stimulus>("stimulus",
                          "the fingertip as perceived (present during approach and hold)");
  s.output<pps::Stimulus>("truth", "the true fingertip (same convention)");
  s.output<TaxelValues>("true_offsets",
                        "per taxel: mean perceived D − true D at the contact events (NaN: never)");
  return s;
}

}  // namespace somasim::plugins
