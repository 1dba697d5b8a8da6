#pragma once
// skin: taxel layouts on the robot's skin patches, contacts -> pressures -> contact events,
// and taxel poses in the root frame every tick.
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/skin/skin_layout.hpp"
#include "somasim/skin/skin_response.hpp"

namespace somasim::plugins {

class SkinPlugin : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::vector<std::string> parts;
    double spacing = 0.0;  // [m]
    int group_size = 0;
    std::string layout_files;
    double contact_radius = 0.01;  // [m]
    skin::PressureModel pressure_model = skin::PressureModel::kShared;
    double pressure_threshold = 0.01;  // [N]
    int min_taxels = 2;
    double release_s = 0.1;  // [s]
    bool figure = true;
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    In<LinkPoses> link_poses;
    OptionalIn<Contacts> contacts_in;
    Out<SkinTaxels> taxels;
    Out<ContactEvents> contacts;
    Out<TaxelValues> pressures;
    template <class V>
    void visit(V& v);
  };
  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
  Config config_;
  Ports ports_;
  /// One body part: its patch, layout, response and statistics.
  struct Part {
    const robot::SkinPatch* patch = nullptr;
    skin::SkinLayout layout;
    std::unique_ptr<skin::PartResponse> response;
    std::size_t events = 0;
    std::set<int> touched_virtual;  // virtual ids named in any event
    // Work skipped when nothing changed (same outputs): the link pose the taxels were last
    // posed at, and whether any contact pressed the part this step / the previous step.
    Eigen::Isometry3d posed_at = Eigen::Isometry3d::Identity();
    bool posed = false;
    bool pressed = false, pressed_before = false;
    // Time of the earliest contact point pressing the part this step, and of the episode
    // (consecutive pressed steps) so far [s]; NaN when unpressed.
    double step_first_touch = std::numeric_limits<double>::quiet_NaN();
    double episode_first_touch = std::numeric_limits<double>::quiet_NaN();
  };

  void select_parts(NodeContext& ctx);
  void load_layouts(NodeContext& ctx);
  void init_outputs();
  void update_poses(const std::vector<Eigen::Isometry3d>& poses);
  void apply_contacts(const Contacts& contacts, const std::vector<Eigen::Isometry3d>& poses);
  void report(NodeContext& ctx);

  std::shared_ptr<const robot::RobotModel> model_;
  skin::ResponseParams response_params_;
  std::vector<Part> parts_;
  std::vector<std::vector<int>> parts_on_link_;  // link index -> indices into parts_
  std::vector<Eigen::Isometry3d> rest_poses_;    // link poses at q = 0 (before any input)
  double keep_events_s_ = 2.0;
  double last_contact_time_ = -1e300;  // newest contact of Contacts::recent already applied [s]
  std::uint64_t next_event_id_ = 1;

  const LinkPoses* link_poses_ = nullptr;
  const Contacts* contacts_ = nullptr;
  SkinTaxels* taxels_ = nullptr;
  ContactEvents* events_ = nullptr;
  TaxelValues* pressures_ = nullptr;
};

}  // namespace somasim::plugins
