#include "somasim/control/chain_selection.hpp"

#include <algorithm>
#include <set>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"
#include "somasim/robot/kinematic_chain.hpp"

namespace somasim::control {

namespace {

ChainSelection make_selection(const robot::RobotModel& model, std::string name,
                              const std::string& tip, const std::string& base) {
  const robot::KinematicChain kc(model, tip, base);  // validates the names and the path
  ChainSelection sel;
  sel.name = std::move(name);
  sel.dofs = kc.dof_indices();
  sel.tip_link = model.frame_ref(tip).link;
  const int base_link = base.empty() ? 0 : model.link_index(base);
  std::set<int> path;  // links strictly below the base, up to the tip link
  for (int l = model.frame_ref(tip).link; l != base_link; l = model.link(l).parent_link)
    path.insert(l);
  // A link belongs to the chain when it is on the path or fixed (through fixed joints only) to
  // a path link: its motion then depends on the chain dofs alone. Links come in topological
  // order, so membership of the parent is known when a child is visited.
  std::vector<bool> member(model.num_links(), false);
  for (int l = 1; l < model.num_links(); ++l) {
    const robot::Link& link = model.link(l);
    member[l] =
        path.count(l) != 0 || (model.joint(link.parent_joint).dof < 0 && member[link.parent_link]);
    if (member[l]) {
      sel.links.push_back(l);
      sel.link_names.push_back(link.name);
    }
  }
  return sel;
}

}  // namespace

bool ChainSelection::contains_link(int link) const {
  return std::find(links.begin(), links.end(), link) != links.end();
}

int ChainSelection::require_link(const robot::RobotModel& model,
                                 const std::string& link_name) const {
  const int l = model.link_index(link_name);
  if (contains_link(l)) return l;
  std::string list;
  for (const auto& n : link_names) list += (list.empty() ? "" : ", ") + n;
  throw InputError("link '" + link_name + "' is not in chain '" + name + "' (links: " + list + ")");
}

ChainSelection select_chain(const robot::RobotModel& model, const std::string& chain_name) {
  const robot::ChainInfo* info = model.find_chain(chain_name);
  if (!info) {
    std::vector<std::string> names;
    for (const auto& c : model.chains()) names.push_back(c.name);
    throw InputError("robot '" + model.name() + "': unknown chain '" + chain_name + "'" +
                     did_you_mean(chain_name, names));
  }
  return make_selection(model, chain_name, info->tip_frame, model.link(info->base_link).name);
}

ChainSelection select_chain(const robot::RobotModel& model, const std::string& tip,
                            const std::string& base) {
  return make_selection(model, (base.empty() ? model.link(0).name : base) + "->" + tip, tip, base);
}

}  // namespace somasim::control
