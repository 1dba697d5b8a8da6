#pragma once
// Internal: the robot-description loader shared by robot_loader.cpp, robot_extends.cpp,
// robot_tree.cpp, robot_chains.cpp, robot_links.cpp and robot_extras.cpp (one concern each).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>
#include <Eigen/Geometry>

#include "robot_yaml.hpp"
#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/units.hpp"

namespace somasim::robot::detail {
namespace fs = std::filesystem;

inline constexpr double kDeg = kRadPerDeg;

inline std::string in_quotes(const std::string& s) {
  return "'" + s + "'";
}

// Reads `path` into a string; `ok` says whether it was a readable regular file. InputError
// for files over 2 MiB.
std::string read_text(const fs::path& path, bool& ok);

struct LinkBuild {
  std::string name;
  YAML::Node decl;        // entry under 'links' (may be undefined)
  YAML::Node decl_key;    // its key node, for messages
  int parent_joint = -1;  // index into joints_
  bool declared = false;
};

struct JointBuild {
  Joint joint;         // parent_link/child_link: indices into links_ (not yet ordered)
  std::string source;  // "chain 'x'" or "joint 'x'", for messages
  std::string parent_name;
  YAML::Node at;           // where to report problems with this joint
  YAML::Node parent_node;  // 'parent' value (explicit joints), to resolve after all links exist
  YAML::Node child_node;
  bool explicit_parent = false;  // an entry under 'joints' (parent resolved by name)
};

// Loads one robot description; see robot_loader.hpp. Member functions are defined in the file
// of their concern (listed per section below).
class RobotLoader {
 public:
  RobotLoader() : reader_(diags_, origins_) {}

  RobotModel load(const std::string& text, const std::string& display_name,
                  const fs::path& base_dir);

 private:
  // --- entry points and orchestration (robot_loader.cpp) -----------------------------------------
  void read(const YAML::Node& root);
  RobotModel build();

  // --- documents, extends and set (robot_extends.cpp) --------------------------------------------
  YAML::Node parse(const std::string& text, const std::string& display);
  YAML::Node resolve(const std::string& text, const std::string& display, const fs::path& dir,
                     int depth, std::vector<fs::path> chain);
  // 'set: {chains.right_arm.links.7.d: -0.1413}': replaces one value of the base description.
  void apply_set(YAML::Node base, const YAML::Node& key, const YAML::Node& value,
                 const std::string& display, const fs::path& dir, const std::string& base_file);
  // yaml-cpp keeps duplicate keys, but lookups see only the first: report them.
  void check_duplicate_keys(const YAML::Node& n);

  // --- kinematic tree: links, joints, parents, ordering (robot_tree.cpp) -------------------------
  int add_link(const std::string& name);
  std::vector<std::string> link_names() const;
  void read_link_declarations(const YAML::Node& links);
  // Sets `child`'s parent joint, or reports a second parent.
  bool attach(int child, int joint, const YAML::Node& at, const std::string& item,
              const std::string& key);
  int add_joint(JointBuild jb);
  // A fixed link `name` under `parent` at `pose` (chain frames after shared joints, chain tips).
  int add_fixed_link(const std::string& name, int parent, const Eigen::Isometry3d& pose,
                     const std::string& source, const YAML::Node& at, const std::string& key);
  // [min, max] (scaled by `unit_scale`), min <= max.
  std::optional<Eigen::Vector2d> read_limits(const YAML::Node& map, const std::string& key,
                                             const std::string& item, const std::string& prefix,
                                             double unit_scale, const std::string& unit);
  void read_joints(const YAML::Node& joints);
  void resolve_joint_parents();
  // Every link reaches the root through its parents: report detached links and cycles.
  void check_tree();
  // Reindexes links depth-first from the root so that parents come first; joint i becomes the
  // parent joint of link i + 1.
  void order_tree();

  // --- DH chains (robot_chains.cpp) --------------------------------------------------------------
  void read_chains(const YAML::Node& chains);
  void read_chain(const std::string& name, const YAML::Node& key, const YAML::Node& node);
  // A chain given by `base` and `tip` only (no DH links): its joints are the movable joints on
  // the tree's path from base to tip, found once the model is built (URDF robots).
  std::vector<ChainInfo> tree_chains(const RobotModel& model);

  // --- link properties: geometry, mass, inertia (robot_links.cpp) --------------------------------
  void read_link_properties();
  std::vector<Geometry> read_geometries(const YAML::Node& link, const std::string& key,
                                        const std::string& item);
  /// `visual`: the shape may carry `colour: [r, g, b]` (in [0, 1]); elsewhere that key is an
  /// unknown key.
  std::optional<Geometry> read_geometry(const YAML::Node& n, const std::string& item,
                                        const std::string& path, bool visual);

  // --- frames, cameras, skin (robot_extras.cpp) --------------------------------------------------
  std::optional<int> find_link(const YAML::Node& map, const std::string& key,
                               const std::string& item, bool required);
  void add_frame(Frame f, const YAML::Node& at, const std::string& item);
  void read_frames(const YAML::Node& frames);
  void read_cameras(const YAML::Node& cameras);
  void read_skin(const YAML::Node& skin);

  struct ChainTip {
    std::string name;
    int link;  // pre-ordering index
    Eigen::Isometry3d pose;
    YAML::Node at;
    std::string item;
  };

  Diagnostics diags_;
  NodeOrigins origins_;
  YamlReader reader_;
  std::string name_, root_name_;
  double density_ = 1000.0;
  std::vector<LinkBuild> links_;
  std::map<std::string, int> link_index_;
  std::vector<JointBuild> joints_;
  std::map<std::string, int> joint_index_;
  int num_dofs_ = 0;
  std::vector<ChainInfo> chains_;
  std::vector<ChainTip> chain_tips_;
  struct TreeChain {
    std::string name;
    YAML::Node key, node;
  };
  std::vector<TreeChain> tree_chains_;
  std::vector<std::string> old_link_names_;
  std::set<std::string> unattached_ok_;  // children of joints that failed to load
  std::vector<Link> built_links_;
  std::vector<Frame> frames_;
  std::vector<Camera> cameras_;
  std::vector<SkinPatch> skin_patches_;
};

}  // namespace somasim::robot::detail
