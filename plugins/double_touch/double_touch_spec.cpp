// double_touch's parameters and ports.
#include "double_touch.hpp"

#include "somasim/robot/experiment_robot.hpp"

namespace somasim::plugins {

template <class V>
void DoubleTouch::Config::visit(V& v) {
  v.block(robot);
  v.field("body_part", body_part)
      .doc("the skin part touched (its link is moved by the other arm's joints)");
  v.field("effector", effector).doc("the touching frame (its origin is the fingertip)");
  v.field("effector_axis", effector_axis)
      .size(3)
      .doc("the finger's pointing direction in the effector frame (brought along -normal)");
  v.field("effector_side", effector_side)
      .size(3)
      .doc(
          "direction from the touching finger toward the other fingers (effector frame); they "
          "are kept across the limb (perpendicular to limb_axis) and lifted by finger_tilt_deg");
  v.field("limb_axis", limb_axis)
      .size(3)
      .doc("the touched limb's long axis in its link frame; zero: the hand's roll is free");
  v.field("finger_tilt_deg", finger_tilt_deg)
      .unit("deg")
      .range(0.0, 60.0)
      .doc(
          "the finger leans this far from -normal (across the limb) so that the longer "
          "neighbouring finger stays off the skin; the fingertip still moves along the normal");
  v.field("finger_radius", finger_radius)
      .unit("m")
      .range(0.0, 0.1)
      .doc("stimulus radius: the ball inscribed in the fingertip");
  v.field("taxels", taxels).doc("taxel ids touched in turn; empty = random reachable taxels");
  v.field("touches", touches)
      .range(1, 100000)
      .doc("touches; the arms then return home and the run stops");
  v.field("start_distance", start_distance)
      .unit("m")
      .range(0.01, 1.0)
      .doc("the approach starts this far from the skin along the normal");
  v.field("press_depth", press_depth)
      .unit("m")
      .range(0.0, 0.02)
      .doc("the approach ends this far below the taxel (a slight press)");
  v.field("align_distance", align_distance)
      .unit("m")
      .range(0.0, 1.0)
      .doc(
          "within this distance of the skin the finger keeps its orientation (axis, tilt, "
          "fingers across the limb); farther out it may lean, up to max_tilt_deg at "
          "start_distance");
  v.field("max_tilt_deg", max_tilt_deg)
      .unit("deg")
      .range(0.0, 90.0)
      .doc("largest lean of the finger from -normal at start_distance");
  v.field("approach_step", approach_step)
      .unit("m")
      .range(0.001, 0.1)
      .doc("spacing of the IK solutions along the approach (joint-space interpolation)");
  v.field("speed_min", speed_min)
      .unit("m/s")
      .range(0.001, 1.0)
      .doc("slowest approach speed of the fingertip");
  v.field("speed_max", speed_max)
      .unit("m/s")
      .range(0.001, 1.0)
      .doc("fastest approach speed (also the retreat speed)");
  v.field("position_jitter", position_jitter)
      .unit("m")
      .range(0.0, 0.05)
      .doc("aimed point: Gaussian σ per tangential axis around the taxel");
  v.field("normal_jitter_deg", normal_jitter_deg)
      .unit("deg")
      .range(0.0, 45.0)
      .doc("approach direction drawn within this angle of the taxel normal");
  v.field("home_posture_deg", home_posture_deg)
      .map_as_text()
      .doc("'joint: value, ...' [deg]: posture regularisation and the final posture");
  v.field("move_duration", move_duration)
      .unit("s")
      .range(0.1, 60.0)
      .doc("joint-space (minimum-jerk) move to the start of each approach");
  v.field("hold", hold).unit("s").range(0.0, 60.0).doc("pause on the skin before retreating");
  v.field("clearance", clearance)
      .unit("m")
      .range(-0.1, 0.2)
      .doc("smallest distance kept between the arms elsewhere (capsule bounds)");
  v.field("position_noise", position_noise)
      .unit("m")
      .range(0.0, 1.0)
      .doc("perceived fingertip position noise (Gaussian σ per axis)");
  v.field("velocity_noise", velocity_noise)
      .unit("m/s")
      .range(0.0, 10.0)
      .doc("perceived fingertip velocity noise (Gaussian σ per axis)");
  v.field("perception", perception)
      .doc(
          "how the robot perceives its fingertip, for `stimulus` and `true_offsets`: "
          "proprioception = the fingertip ball of the believed arm kinematics; vision = the "
          "marker seen by ideal eyes: a ball of marker_radius centred on the TRUE effector "
          "origin (the arm's joint offsets do not enter; wire a marker tracker's stimulus to "
          "the learner and compare with these offsets)");
  v.field("marker_radius", marker_radius)
      .unit("m")
      .range(0.0, 0.1)
      .doc("radius of the fingertip marker (perception: vision)");
}

template <class V>
void DoubleTouch::Ports::visit(V& v) {
  v.port("state", state, "true joint values (world.joint_state)");
  v.port("taxels", taxels, "skin taxels posed by the true kinematics (skin.taxels)");
  v.port("contacts", contacts, "skin contact events (skin.contacts)");
  v.port("believed_state", believed_state,
         "joint values the robot believes (default: the true ones)");
  v.port("believed_taxels", believed_taxels,
         "taxels posed by the believed kinematics (the learner's; for true_offsets)");
  v.port("command", command, "position commands (with velocity feed-forward), both arms");
  v.port("stimulus", stimulus, "the fingertip as perceived (present during approach and hold)");
  v.port("truth", truth, "the true fingertip (same convention)");
  v.port("true_offsets", true_offsets,
         "per taxel: mean perceived D − true D at the contact events (NaN: never)");
}

// configure() (double_touch.cpp) fills the config and binds the ports with these.
template void DoubleTouch::Config::visit(ConfigFields&);
template void DoubleTouch::Ports::visit(PortBinder&);

void DoubleTouch::Config::validate(ConfigChecks& checks) const {
  checks.require(
      Eigen::Vector3d(effector_axis[0], effector_axis[1], effector_axis[2]).norm() >= 1e-9,
      effector_axis, "must not be zero");
  checks.require(speed_max >= speed_min, speed_max, "must not be less than speed_min");
}

PluginSpec DoubleTouch::spec() {
  return make_plugin_spec<Config, Ports>(
      "double_touch",
      "Self-touch for tactile-motor PPS learning: the right index fingertip touches "
      "taxels of the left forearm along their normals (both arms solved together), "
      "approaching from start_distance at speed_min..speed_max, again and again; the "
      "stimulus is the fingertip from the believed kinematics (proprioception) + noise.");
}

}  // namespace somasim::plugins
