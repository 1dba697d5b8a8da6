#include "blowup_detector.hpp"

#include <cmath>

#include <fmt/format.h>

#include "bullet_math.hpp"
#include "somasim/error.hpp"

namespace somasim::bullet_world {

void check_blowup(const RobotMultiBody& robot, const ObjectManager& objects,
                  const Penetration& deepest, const BlowupLimits& limits, double t) {
  const robot::RobotModel& model = robot.model();
  const auto fail = [t](const std::string& what) {
    throw RunError(fmt::format("physics blow-up at t = {:.3f} s: {}", t, what));
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
  for (int i = 0; i < objects.size(); ++i) {
    if (!objects.present(i)) continue;
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
