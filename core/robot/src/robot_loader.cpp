// Loading a robot description: YAML (+ extends/set) → links, DH chains, joints → a validated,
// topologically ordered RobotModel. The format is documented in assets/robots/README.md.
// The loader is split by concern; see robot_loader_internal.hpp.
#include "somasim/robot/robot_loader.hpp"

#include <fstream>
#include <sstream>

#include "robot_loader_internal.hpp"
#include "urdf_import.hpp"

namespace somasim::robot::detail {

namespace {

const std::vector<std::string> kTopKeys = {"robot",   "extends", "set",    "root",
                                           "density", "links",   "joints", "chains",
                                           "frames",  "cameras", "skin"};

}  // namespace

std::string read_text(const fs::path& path, bool& ok) {
  // As for experiment files: the YAML parser's memory grows ~200x the file size.
  constexpr std::uintmax_t kMaxRobotFileBytes = 2u << 20;
  std::error_code ec;
  if (const auto size = fs::file_size(path, ec); !ec && size > kMaxRobotFileBytes)
    throw InputError("robot description '" + path.string() + "' is " + std::to_string(size) +
                     " bytes; at most " + std::to_string(kMaxRobotFileBytes) + " (2 MiB) are read");
  // Never opened unless a regular file: opening a FIFO blocks, a device never ends.
  ok = fs::is_regular_file(path, ec);
  if (!ok) return "";
  std::ifstream in(path, std::ios::binary);
  ok = static_cast<bool>(in);
  std::stringstream s;
  if (ok) s << in.rdbuf();
  return s.str();
}

RobotModel RobotLoader::load(const std::string& text, const std::string& display_name,
                             const fs::path& base_dir) {
  YAML::Node root = resolve(text, display_name, base_dir, 0, {});
  read(root);
  diags_.throw_if_any();
  return build();
}

void RobotLoader::read(const YAML::Node& root) {
  reader_.check_keys(root, kTopKeys, "", "");
  name_ = reader_.string(root, "robot", "", "", true).value_or("robot");
  root_name_ = reader_.string(root, "root", "", "", false).value_or("root");
  density_ =
      reader_.positive(root, "density", "", "", false, "a density", "kg/m^3").value_or(1000.0);
  add_link(root_name_);
  const std::size_t errors_before_tree = diags_.items().size();
  read_link_declarations(root["links"]);
  read_chains(root["chains"]);
  read_joints(root["joints"]);
  resolve_joint_parents();
  check_tree();
  if (diags_.items().size() != errors_before_tree) return;  // the rest needs a sound tree
  for (const auto& l : links_) old_link_names_.push_back(l.name);
  order_tree();
  read_link_properties();
  read_frames(root["frames"]);
  read_cameras(root["cameras"]);
  read_skin(root["skin"]);
}

RobotModel RobotLoader::build() {
  std::vector<Joint> joints;
  for (auto& jb : joints_) joints.push_back(std::move(jb.joint));
  for (auto& c : chains_) c.base_link = link_index_.at(old_link_names_.at(c.base_link));
  RobotModel model(name_, std::move(built_links_), std::move(joints), std::move(frames_),
                   std::move(cameras_), std::move(skin_patches_), std::move(chains_));
  if (tree_chains_.empty()) return model;
  std::vector<ChainInfo> chains = model.chains();
  for (ChainInfo& c : tree_chains(model)) chains.push_back(std::move(c));
  return RobotModel(model.name(), model.links(), model.joints(), model.frames(), model.cameras(),
                    model.skin_patches(), std::move(chains));
}

}  // namespace somasim::robot::detail

namespace somasim::robot {
namespace fs = std::filesystem;

RobotModel parse_robot_model(const std::string& text, const std::string& display_name,
                             const fs::path& base_dir) {
  detail::RobotLoader loader;
  return loader.load(text, display_name, base_dir);
}

RobotModel load_robot_model(const fs::path& file) {
  bool ok = false;
  const std::string text = detail::read_text(file, ok);
  const bool urdf = detail::is_urdf_file(file);
  if (!ok)
    throw InputError("cannot read robot description '" + file.string() + "'; expected a readable " +
                     (urdf ? "URDF" : "YAML") + " file");
  if (urdf) return parse_urdf_robot_model(text, file.string(), file.parent_path());
  return parse_robot_model(text, file.string(), file.parent_path());
}

RobotModel parse_urdf_robot_model(const std::string& xml, const std::string& display_name,
                                  const fs::path& base_dir) {
  return parse_robot_model(detail::urdf_to_description(xml, display_name, base_dir),
                           display_name + " (as converted from URDF)", base_dir);
}

std::shared_ptr<const RobotModel> load_robot_model_shared(const fs::path& file) {
  return std::make_shared<const RobotModel>(load_robot_model(file));
}

}  // namespace somasim::robot
