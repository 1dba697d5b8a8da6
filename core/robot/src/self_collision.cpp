#include "somasim/robot/self_collision.hpp"

namespace somasim::robot {

std::vector<std::vector<bool>> collision_exempt_links(const RobotModel& model,
                                                      const std::vector<bool>& locked) {
  const int n = model.num_links();
  // Rigid group of each link: the link reached by walking up through fixed or locked joints.
  auto rigid = [&](int link) {
    const int j = model.link(link).parent_joint;
    if (j < 0) return false;
    const int dof = model.joint(j).dof;
    return dof < 0 || (!locked.empty() && locked[dof]);
  };
  std::vector<int> group(n);
  for (int i = 0; i < n; ++i) {
    int g = i;
    while (rigid(g)) g = model.link(g).parent_link;
    group[i] = g;
  }
  std::vector<bool> group_has_geometry(n, false);
  for (int i = 0; i < n; ++i)
    if (!model.link(i).collision.empty()) group_has_geometry[group[i]] = true;
  // Nearest ancestor group with geometry (-1 for none).
  std::vector<int> geometric_parent(n, -1);
  for (int i = 0; i < n; ++i) {
    int p = model.link(group[i]).parent_link;
    while (p >= 0 && !group_has_geometry[group[p]]) p = model.link(group[p]).parent_link;
    geometric_parent[i] = p >= 0 ? group[p] : -1;
  }
  std::vector<std::vector<bool>> exempt(n, std::vector<bool>(n, false));
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      exempt[a][b] = group[a] == group[b] || geometric_parent[a] == group[b] ||
                     geometric_parent[b] == group[a];
  return exempt;
}

}  // namespace somasim::robot
