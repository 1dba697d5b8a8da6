#include "blowup_detector.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "bullet_math.hpp"
#include "somasim/error.hpp"

namespace somasim::bullet_world {

namespace {

std::string contact_body_name(int link, int object, const robot::RobotModel& model,
                              const ObjectManager& objects) {
  if (link >= 0 && link < model.num_links()) return fmt::format("link '{}'", model.link(link).name);
  if (object >= 0 && object < objects.size())
    return fmt::format("object '{}'", objects.name(object));
  return "an unknown body";
}

}  // namespace

std::string contact_pairs_text(const robot::RobotModel& model, const ObjectManager& objects,
                               const Contacts& contacts, std::size_t max_pairs) {
  // Pairs in order of first appearance, each with its largest normal force.
  std::vector<std::pair<std::string, double>> pairs;
  std::map<std::string, std::size_t> index;
  for (const Contact& c : contacts.points) {
    const std::string name = contact_body_name(c.link_a, c.object_a, model, objects) + " - " +
                             contact_body_name(c.link_b, c.object_b, model, objects);
    const auto [it, added] = index.emplace(name, pairs.size());
    if (added) pairs.emplace_back(name, c.normal_force);
    pairs[it->second].second = std::max(pairs[it->second].second, c.normal_force);
  }
  if (pairs.empty()) return "no bodies in contact";
  std::string text = "bodies in contact: ";
  for (std::size_t i = 0; i < pairs.size() && i < max_pairs; ++i)
    text += fmt::format("{}{} ({:.1f} N)", i ? ", " : "", pairs[i].first, pairs[i].second);
  if (pairs.size() > max_pairs) text += fmt::format(" and {} more pairs", pairs.size() - max_pairs);
  return text;
}

void check_blowup(const RobotMultiBody& robot, const ObjectManager& objects,
                  const Contacts& contacts, const Penetration& deepest, const BlowupLimits& limits,
                  double t) {
  const robot::RobotModel& model = robot.model();
  const auto fail = [&](const std::string& what) {
    throw RunError(fmt::format("physics blow-up at t = {:.3f} s: {}; {}", t, what,
                               contact_pairs_text(model, objects, contacts)));
  };
  for (int d = 0; d < model.num_dofs(); ++d) {
    const double q = robot.position(d), dq = robot.velocity(d);
    const std::string& name = model.joint(model.dof_joint(d)).name;
    if (!std::isfinite(q) || !std::isfinite(dq))
      fail(fmt::format("joint '{}' has a non-finite state (q = {}, dq = {})", name, q, dq));
    if (std::abs(dq) > limits.max_joint_speed)
      fail(fmt::format("joint '{}' moves at {:.1f} rad/s (max_joint_speed: {} rad/s)", name,
                       std::abs(dq), limits.max_joint_speed));
  }
  for (int i : objects.live()) {
    const btRigidBody& body = objects.body(i);
    const Eigen::Vector3d v = to_eigen(body.getLinearVelocity());
    if (!to_eigen(body.getWorldTransform()).matrix().allFinite() || !v.allFinite() ||
        !to_eigen(body.getAngularVelocity()).allFinite())
      fail(fmt::format("object '{}' has a non-finite state", objects.name(i)));
    if (v.norm() > limits.max_object_speed)
      fail(fmt::format("object '{}' moves at {:.1f} m/s (max_object_speed: {} m/s)",
                       objects.name(i), v.norm(), limits.max_object_speed));
  }
  if (deepest.depth > limits.max_penetration)
    fail(fmt::format("{} and {} interpenetrate by {:.1f} mm (max_penetration: {} mm)",
                     body_name(deepest.a, model, objects), body_name(deepest.b, model, objects),
                     deepest.depth * 1e3, limits.max_penetration * 1e3));
}

}  // namespace somasim::bullet_world
