#include "somasim/control/touch_planner.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include "somasim/units.hpp"

namespace somasim::control {

namespace {

bool moved_by(const robot::RobotModel& model, int link, const std::vector<int>& dofs) {
  for (int d : model.supporting_dofs(link))
    if (std::find(dofs.begin(), dofs.end(), d) != dofs.end()) return true;
  return false;
}

}  // namespace

void TouchPath::sample(double d, Eigen::VectorXd& q, Eigen::VectorXd* dq_dd) const {
  // `distance` decreases: outside the path hold its ends (no motion).
  if (distance.size() == 1 || d >= distance.front() || d <= distance.back()) {
    q = d <= distance.back() ? posture.back() : posture.front();
    if (dq_dd) dq_dd->setZero(q.size());
    return;
  }
  std::size_t k = 0;
  while (distance[k + 1] > d) ++k;  // distance[k] > d >= distance[k + 1]
  const double span = distance[k] - distance[k + 1];
  q = posture[k] + ((distance[k] - d) / span) * (posture[k + 1] - posture[k]);
  if (dq_dd) *dq_dd = (posture[k] - posture[k + 1]) / span;
}

void TouchPath::sample(double d, const std::function<double(const Eigen::VectorXd&)>& measure,
                       Eigen::VectorXd& q, Eigen::VectorXd* dq_dd) const {
  if (distance.size() == 1 || d >= distance.front() || d <= distance.back()) {
    sample(d, q, dq_dd);
    return;
  }
  std::size_t k = 0;
  while (distance[k + 1] > d) ++k;
  const Eigen::VectorXd& a = posture[k];
  const Eigen::VectorXd& b = posture[k + 1];
  // f(s) = measure(a + s (b − a)) − d, bracketed by the segment's ends.
  double s0 = 0.0, s1 = 1.0, f0 = measure(a) - d, f1 = measure(b) - d;
  if (f0 <= 0.0 || f1 >= 0.0) {  // the waypoints' own IK residuals put d outside: interpolate
    sample(d, q, dq_dd);
    return;
  }
  double s = f0 / (f0 - f1);
  for (int it = 0; it < 6; ++it) {
    const double f = measure(a + s * (b - a)) - d;
    if (std::abs(f) < 1e-7) break;
    if ((f > 0) == (f0 > 0)) {
      s0 = s;
      f0 = f;
    } else {
      s1 = s;
      f1 = f;
    }
    s = std::abs(f0 - f1) > 1e-15 ? s0 + f0 * (s1 - s0) / (f0 - f1) : 0.5 * (s0 + s1);
  }
  q = a + s * (b - a);
  // ds/dd from the bracketing secant (the local slope of the measured distance).
  if (dq_dd) *dq_dd = (b - a) * ((s1 - s0) / std::min(f1 - f0, -1e-12));
}

TouchPlanner::TouchPlanner(std::shared_ptr<const robot::RobotModel> model, TouchIk ik,
                           TouchPlannerOptions options)
    : model_(std::move(model)), ik_(std::move(ik)), options_(options), data_(*model_) {
  const auto& solved = ik_.solved_dofs();
  const std::vector<int> effector_dofs(solved.begin(), solved.begin() + ik_.effector_dofs());
  std::vector<int> a, b;
  for (int l = 0; l < model_->num_links(); ++l) {
    if (model_->link(l).collision.empty()) continue;
    (moved_by(*model_, l, effector_dofs) ? a : b).push_back(l);
  }
  std::vector<LinkClearance::Ignored> ignored;
  // The touching shape on the touched link: the effector link's shape nearest the contact point.
  const robot::FrameRef& eff = ik_.effector();
  int touching = -1;
  double nearest = 1e300;
  for (const auto& c : link_capsules(*model_, eff.link)) {
    const Eigen::Vector3d p = eff.pose.translation();
    const double dist = segment_distance(p, p, c.a, c.b) - c.radius;
    if (dist < nearest) {
      nearest = dist;
      touching = c.shape;
    }
  }
  ignored.push_back({eff.link, touching, ik_.target_link()});
  // A moving link always touches its nearest ancestor with geometry (the shoulder): skip it.
  for (int l : a) {
    int g = model_->link(l).parent_link;
    while (g > 0 && model_->link(g).collision.empty()) g = model_->link(g).parent_link;
    if (g >= 0 && std::find(a.begin(), a.end(), g) == a.end()) ignored.push_back({l, -1, g});
  }
  check_ = std::make_unique<LinkClearance>(*model_, a, b, std::move(ignored));
}

double TouchPlanner::clearance(const Eigen::VectorXd& q, std::string* detail) {
  robot::forward_kinematics(*model_, data_, q);
  const auto r = check_->check(data_.link_poses);
  if (detail && r.link_a >= 0)
    *detail = fmt::format("'{}' (shape {}) comes within {:.1f} mm of '{}' (shape {})",
                          model_->link(r.link_a).name, r.shape_a, 1000.0 * r.distance,
                          model_->link(r.link_b).name, r.shape_b);
  return r.distance;
}

TouchTarget TouchPlanner::at(TouchTarget target, double d) const {
  target.distance = d;
  if (d > options_.align_distance) {
    // Far out only the fingertip's path matters: the finger may lean from −n, more and more up
    // to max_tilt at start_distance (a small weight: the position comes first), and roll.
    const double span = std::max(options_.start_distance - options_.align_distance, 1e-9);
    double tol = ik_.options().axis_tolerance;
    target.axis_weight = options_.far_axis_weight;
    // The other fingers are far from the skin: the roll is free and the goal is −n itself.
    tol += target.tilt;
    target.tangent.setZero();
    target.axis_tolerance =
        tol + (options_.max_tilt - tol) * std::min(1.0, (d - options_.align_distance) / span);
  }
  return target;
}

bool TouchPlanner::solve_at(const TouchTarget& target, const Eigen::VectorXd& home, double d,
                            Eigen::VectorXd& q, std::string& detail) {
  TouchTarget t = at(target, d);
  t.target_dof_cost = options_.limb_cost;
  const auto r = ik_.solve(t, home, q);
  if (!r.success) {
    detail =
        fmt::format("no posture at {:.3f} m from the skin (residual {:.1f} mm, axis {:.1f} deg)", d,
                    1000.0 * r.position_error, rad_to_deg(r.axis_error));
    return false;
  }
  if (clearance(q, &detail) < options_.clearance) return false;
  return true;
}

bool TouchPlanner::refine(const TouchTarget& target, const Eigen::VectorXd& home, double d0,
                          const Eigen::VectorXd& q0, double d1, const Eigen::VectorXd& q1,
                          int depth, TouchPath& path, std::string& detail) {
  // Joint-space interpolation between two IK solutions may swing the fingertip off the normal,
  // and a restart of the IK may land on another arm posture (a jump the motors cannot follow):
  // halve such segments; a jump survives the halvings and rejects the plan.
  const double dm = 0.5 * (d0 + d1);
  Eigen::VectorXd qm = 0.5 * (q0 + q1);
  TouchTarget tm = at(target, dm);
  const double stray = ik_.evaluate(tm, qm).position_error;
  const double rate = (q1 - q0).cwiseAbs().maxCoeff() / std::max(std::abs(d1 - d0), 1e-12);
  if (stray <= options_.path_tolerance && rate <= options_.max_joint_rate) {
    path.distance.push_back(d1);
    path.posture.push_back(q1);
    return true;
  }
  if (depth >= options_.max_refinements) {
    detail = fmt::format("the posture jumps between {:.4f} and {:.4f} m from the skin", d0, d1);
    return false;
  }
  if (!solve_at(target, home, dm, qm, detail)) return false;
  return refine(target, home, d0, q0, dm, qm, depth + 1, path, detail) &&
         refine(target, home, dm, qm, d1, q1, depth + 1, path, detail);
}

bool TouchPlanner::sweep(const TouchTarget& target, const Eigen::VectorXd& home, double d_from,
                         const std::vector<double>& ds, Eigen::VectorXd q, TouchPath& path,
                         std::string& detail) {
  double d_prev = d_from;
  for (double d : ds) {
    const Eigen::VectorXd q_prev = q;
    if (!solve_at(target, home, d, q, detail)) return false;
    if (!refine(target, home, d_prev, q_prev, d, q, 0, path, detail)) return false;
    d_prev = d;
  }
  return true;
}

PlanResult TouchPlanner::plan(const TouchTarget& target, const Eigen::VectorXd& home,
                              const Eigen::VectorXd& from, TouchPath& path, std::string& detail) {
  const double d_in = -options_.press_depth, d_out = options_.start_distance;
  bool collision = false;
  detail.clear();
  // Where the limb is presented: the posture of both arms with the fingertip at `d_present`;
  // the limb then stays there and the effector's arm alone follows the normal both ways.
  for (const double d_present : {std::clamp(options_.align_distance, d_in, d_out), d_in,
                                 0.5 * (options_.align_distance + d_out)}) {
    path.distance.clear();
    path.posture.clear();
    Eigen::VectorXd q = home;
    const auto r = ik_.solve(at(target, d_present), home, q);
    if (!r.success) {
      detail += (detail.empty() ? "" : "; ") +
                fmt::format(
                    "no posture of both arms at {:.3f} m from the skin (residual {:.1f} mm, axis "
                    "{:.1f} deg)",
                    d_present, 1000.0 * r.position_error, rad_to_deg(r.axis_error));
      continue;
    }
    std::vector<double> out, in;  // from d_present outwards / inwards
    for (double d = d_present + options_.step; d < d_out - 1e-9; d += options_.step)
      out.push_back(d);
    out.push_back(d_out);
    for (double d = d_present - options_.step; d > d_in + 1e-9; d -= options_.step) in.push_back(d);
    if (d_present > d_in + 1e-9) in.push_back(d_in);
    TouchPath outward, inward;
    outward.distance = {d_present};
    outward.posture = {q};
    std::string why;
    if (!sweep(target, q, d_present, out, q, outward, why) ||
        !sweep(target, q, d_present, in, q, inward, why)) {
      collision = collision || why.find("comes within") != std::string::npos;
      detail += (detail.empty() ? "" : "; ") + fmt::format("limb at {:.3f} m: {}", d_present, why);
      continue;
    }
    // Ordered from the start of the approach to the press.
    path.distance.assign(outward.distance.rbegin(), outward.distance.rend());
    path.posture.assign(outward.posture.rbegin(), outward.posture.rend());
    path.distance.insert(path.distance.end(), inward.distance.begin(), inward.distance.end());
    path.posture.insert(path.posture.end(), inward.posture.begin(), inward.posture.end());
    // The joint-space move to the start of the approach (straight in joint space).
    bool clear = true;
    for (int k = 1; k < options_.transfer_checks && clear; ++k) {
      const double s = static_cast<double>(k) / options_.transfer_checks;
      if (clearance(from + s * (path.posture.front() - from), &detail) < options_.clearance) {
        detail = "on the way to the start: " + detail;
        clear = false;
      }
    }
    if (clear) return PlanResult::kOk;
    collision = true;
  }
  return collision ? PlanResult::kCollision : PlanResult::kUnreachable;
}

}  // namespace somasim::control
