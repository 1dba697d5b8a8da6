#include "somasim/robot/robot_model.hpp"

#include <algorithm>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"

namespace somasim::robot {

std::string_view joint_type_name(JointType type) {
  switch (type) {
    case JointType::Revolute:
      return "revolute";
    case JointType::Prismatic:
      return "prismatic";
    case JointType::Fixed:
      return "fixed";
  }
  return "?";
}

RobotModel::RobotModel(std::string name, std::vector<Link> links, std::vector<Joint> joints,
                       std::vector<Frame> frames, std::vector<Camera> cameras,
                       std::vector<SkinPatch> skin_patches, std::vector<ChainInfo> chains)
    : name_(std::move(name)),
      links_(std::move(links)),
      joints_(std::move(joints)),
      frames_(std::move(frames)),
      cameras_(std::move(cameras)),
      skin_patches_(std::move(skin_patches)),
      chains_(std::move(chains)) {
  SOMASIM_CHECK(!links_.empty(), "a robot model needs a root link");
  SOMASIM_CHECK(links_[0].parent_joint == -1, "link 0 must be the root");
  SOMASIM_CHECK(joints_.size() + 1 == links_.size(), "one parent joint per non-root link");
  int num_dofs = 0;
  for (const auto& j : joints_)
    if (j.dof >= 0) num_dofs = std::max(num_dofs, j.dof + 1);
  dof_joints_.assign(num_dofs, -1);
  lower_.resize(num_dofs);
  upper_.resize(num_dofs);
  for (int i = 0; i < num_joints(); ++i) {
    const Joint& j = joints_[i];
    SOMASIM_CHECK((j.type == JointType::Fixed) == (j.dof < 0), "fixed joints have no dof");
    SOMASIM_CHECK(j.parent_link >= 0 && j.parent_link < j.child_link && j.child_link < num_links(),
                  "links must be in topological order");
    SOMASIM_CHECK(
        links_[j.child_link].parent_joint == i && links_[j.child_link].parent_link == j.parent_link,
        "link/joint cross references disagree");
    if (j.dof >= 0) {
      SOMASIM_CHECK(dof_joints_[j.dof] == -1, "each dof belongs to one joint");
      dof_joints_[j.dof] = i;
      lower_[j.dof] = j.lower;
      upper_[j.dof] = j.upper;
    }
  }
  for (int d : dof_joints_) SOMASIM_CHECK(d >= 0, "dofs must be numbered 0..n-1");
  supporting_dofs_.resize(links_.size());
  for (int l = 1; l < num_links(); ++l) {
    const Joint& j = joints_[links_[l].parent_joint];
    supporting_dofs_[l] = supporting_dofs_[j.parent_link];
    if (j.dof >= 0) supporting_dofs_[l].push_back(j.dof);
  }
  for (const auto& f : frames_) SOMASIM_CHECK(f.link >= 0 && f.link < num_links(), "frame link");
  for (const auto& c : cameras_) SOMASIM_CHECK(c.link >= 0 && c.link < num_links(), "camera link");
}

namespace {
template <class T>
int index_of(const std::vector<T>& items, const std::string& name) {
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].name == name) return static_cast<int>(i);
  return -1;
}
template <class T>
std::vector<std::string> names_of(const std::vector<T>& items) {
  std::vector<std::string> out;
  for (const auto& i : items) out.push_back(i.name);
  return out;
}
}  // namespace

int RobotModel::find_link(const std::string& name) const {
  return index_of(links_, name);
}
int RobotModel::find_joint(const std::string& name) const {
  return index_of(joints_, name);
}
int RobotModel::find_frame(const std::string& name) const {
  return index_of(frames_, name);
}
int RobotModel::find_camera(const std::string& name) const {
  return index_of(cameras_, name);
}
const ChainInfo* RobotModel::find_chain(const std::string& name) const {
  const int i = index_of(chains_, name);
  return i < 0 ? nullptr : &chains_[i];
}

int RobotModel::link_index(const std::string& name) const {
  const int i = find_link(name);
  if (i < 0)
    throw InputError("robot '" + name_ + "': unknown link '" + name + "'" +
                     did_you_mean(name, names_of(links_)));
  return i;
}

int RobotModel::joint_index(const std::string& name) const {
  const int i = find_joint(name);
  if (i < 0)
    throw InputError("robot '" + name_ + "': unknown joint '" + name + "'" +
                     did_you_mean(name, names_of(joints_)));
  return i;
}

int RobotModel::dof_index(const std::string& joint_name) const {
  const Joint& j = joints_[joint_index(joint_name)];
  if (j.dof < 0)
    throw InputError("robot '" + name_ + "': joint '" + joint_name +
                     "' is fixed; expected a revolute or prismatic joint");
  return j.dof;
}

FrameRef RobotModel::frame_ref(const std::string& name) const {
  if (const int f = find_frame(name); f >= 0) return {frames_[f].link, frames_[f].pose};
  if (const int l = find_link(name); l >= 0) return {l, Eigen::Isometry3d::Identity()};
  std::vector<std::string> all = names_of(frames_);
  for (const auto& l : links_) all.push_back(l.name);
  throw InputError("robot '" + name_ + "': unknown frame or link '" + name + "'" +
                   did_you_mean(name, all));
}

double RobotModel::total_mass() const {
  double m = 0;
  for (const auto& l : links_) m += l.inertial.mass;
  return m;
}

}  // namespace somasim::robot
