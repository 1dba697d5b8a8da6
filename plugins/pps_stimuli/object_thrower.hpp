#pragma once
// object_thrower: the experimenter's stand-in for PPS learning and evaluation with objects
// (Roncone et al. 2016, Learning peripersonal space representation through artificial skin for
// avoidance and reaching with whole body surface, exp. 3).
//
// One object at a time, aimed at a random taxel of a part; parts, `shapes` and `motions`
// (approach / static / receding; geometry in presentation_plan.hpp) are each taken in turn with
// the presentation index (lists of coprime lengths visit every combination); the world removes it
// at the end of its lifetime, and the next one follows after `pause`. With `link_poses` wired,
// start points are clear of the robot and paths clear of every link but the aimed one (a taxel
// no such path reaches is given up for another; unreachable_draws counts them). Objects are
// guided by default (a held object: stopped by what it meets; bullet_world's guide_max_force);
// with `world_contacts`, touches of any robot link are counted (robot_contact_*), and
// withdraw_after_robot_contact ends a presentation that meets the robot anywhere. With `view`,
// each presentation is checked against the cameras (presentation_view.hpp): reported as in or
// out of view, or (require) drawn again until the eyes can see it coming.
//
// `truth` is the object's centre and velocity (root frame) read back from the world.
// `stimulus` is what the robot perceives: the truth plus Gaussian noise, placed through the
// believed head/eye kinematics when `believed_state` is wired (believed_vision.hpp), else as is.
// `true_offsets` (with `contacts`): per taxel, the mean over its skin contact events of
// perceived D − true D (somasim/pps/true_offsets.hpp), the taxels posed by `believed_taxels` for
// the perceived D (by the true `taxels` when unwired).
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <span>

#include "believed_vision.hpp"
#include "presentation_plan.hpp"
#include "presentation_view.hpp"
#include "robot_contact_log.hpp"
#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/pps/true_offsets.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"
#include "somasim/skin/ports.hpp"

namespace somasim::plugins {

/// What of a cube meets the aimed taxel.
enum class BoxFacing : std::uint8_t { kFace, kCorner };
/// "face", "corner".
inline constexpr NamedValue<BoxFacing> kBoxFacingNames[] = {{BoxFacing::kFace, "face"},
                                                            {BoxFacing::kCorner, "corner"}};
constexpr std::span<const NamedValue<BoxFacing>> name_table(BoxFacing) {
  return kBoxFacingNames;
}

class ObjectThrower : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::vector<std::string> parts{"left_forearm", "right_palm"};
    std::vector<std::string> shapes{"sphere", "box"};
    std::vector<std::string> motions{"approach"};
    double size = 0.025;  // [m]
    BoxFacing box_facing = BoxFacing::kFace;
    double cylinder_half_height = 0.04;  // [m]
    CylinderAxis cylinder_axis = CylinderAxis::kAny;
    double path_clearance = 0.005;     // [m]
    double distance_min = 0.20;        // [m]
    double distance_max = 0.30;        // [m]
    double receding_start_min = 0.05;  // [m]
    double receding_start_max = 0.10;  // [m]
    double static_duration = 2.0;      // [s]
    double cone_deg = 45.0;            // [deg]
    double speed_min = 0.05;           // [m/s]
    double speed_max = 0.15;           // [m/s]
    int approaches = 20;
    double pause = 1.0;                          // [s]
    double first_after = 0.0;                    // [s]
    double linger = 0.1;                         // [s]
    double withdraw_after_skin_contact = -1.0;   // [s]
    double withdraw_after_robot_contact = -1.0;  // [s]
    double wait_for_clear_path = 10.0;           // [s]
    std::string object_motion = "guided";
    double mass = 0.1;  // [kg]
    ViewPolicy view = ViewPolicy::kReport;
    std::vector<std::string> view_cameras;
    double view_until = 0.05;     // [m]
    double view_margin = 10.0;    // [px]
    double position_noise = 0.0;  // [m]
    double velocity_noise = 0.0;  // [m/s]
    std::string vision_link;
    template <class V>
    void visit(V& v);
    void validate(ConfigChecks& checks) const;  // cross-field checks
  };
  struct Ports {
    In<SkinTaxels> taxels;
    In<JointState> state;
    In<ObjectStates> objects;
    OptionalIn<JointState> believed_state;
    OptionalIn<LinkPoses> link_poses;
    OptionalIn<ContactEvents> contacts;
    OptionalIn<Contacts> world_contacts;
    OptionalIn<SkinTaxels> believed_taxels;
    OptionalIn<pps::Stimulus> learner_stimulus;
    Out<ObjectSpawns> spawns;
    Out<pps::Stimulus> stimulus;
    Out<pps::Stimulus> truth;
    Out<Presentation> presentation;
    Out<TaxelValues> true_offsets;
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
  void read_lists(NodeContext& ctx);
  void configure_view(NodeContext& ctx);
  /// Presents the next object; false (unplaced_ says why) when no clear path reaches its part.
  bool launch(NodeContext& ctx);
  /// launch(), or wait for a clear path (wait_for_clear_path_), then a RunError.
  void try_launch(NodeContext& ctx, double now);
  void perceive(NodeContext& ctx);
  void learn_true_offsets();
  /// Sets the current object's withdrawal withdraw_after_skin_contact_ after the skin first felt
  /// it.
  void withdraw_when_felt();
  /// Logs the current object's touches of robot links; withdraws it
  /// withdraw_after_robot_contact_ after the first.
  void watch_robot_contacts(NodeContext& ctx);
  /// The current object goes at `time_s` [s] or earlier.
  void withdraw_at(double time_s);
  /// Asks the world to remove the current object once its withdrawal time has come.
  void withdraw_if_due(double now);
  /// The median of learner_radii_ (not empty) [m].
  double median_learner_radius() const;

  std::shared_ptr<const robot::RobotModel> model_;
  std::unique_ptr<BelievedVision> vision_;  // set when believed_state is wired
  std::vector<ObjectShape> shapes_;
  std::vector<PresentationMotion> motions_;
  PresentationGeometry geometry_;
  bool box_corner_ = false;
  int reduced_clearance_ = 0;      // presentations placed with the least clearance
  int paths_met_beside_skin_ = 0;  // paths that met the aimed link beside its skin
  int turned_about_normal_ = 0;    // presentations placed only once turned about the normal
  double withdraw_at_s_ = 0.0;     // when the current object goes (inf: not yet)
  ObjectMotion object_motion_ = ObjectMotion::kGuided;
  double retry_at_s_ = 0.0;  // no launch before this time (first_after, then retries) [s]
  std::optional<double> waiting_since_s_;            // first failed launch of the current wait [s]
  std::string unplaced_;                             // why the last launch failed
  int postponed_ = 0;                                // failed launches
  const Contacts* world_contacts_ = nullptr;         // optional
  std::unique_ptr<RobotContactLog> robot_contacts_;  // set when world_contacts is wired
  std::uint64_t last_felt_event_id_ = 0;
  int withdrawn_ = 0;
  double cylinder_half_height_ = 0, position_noise_ = 0, velocity_noise_ = 0, pause_ = 0;
  const SkinTaxels* skin_ = nullptr;
  const JointState* state_ = nullptr;
  const JointState* believed_state_ = nullptr;  // optional
  const ObjectStates* objects_ = nullptr;
  const LinkPoses* link_poses_ = nullptr;            // optional
  const ContactEvents* contacts_ = nullptr;          // optional
  const SkinTaxels* believed_taxels_ = nullptr;      // optional
  const pps::Stimulus* learner_stimulus_ = nullptr;  // optional
  std::vector<double> learner_radii_;  // its radius [m] while the current object is presented
  int true_offset_events_unseen_ = 0;  // contact events the learner never saw the object of
  ObjectSpawns* spawns_ = nullptr;
  pps::Stimulus* stimulus_ = nullptr;
  pps::Stimulus* truth_ = nullptr;
  Presentation* presentation_ = nullptr;
  TaxelValues* true_offsets_out_ = nullptr;

  double lifetime_ = 0.0;  // of the current object [s]
  double radius_ = 0.0;    // its stimulus radius: centre to skin at contact [m]
  int launched_ = 0;
  std::uint64_t next_spawn_id_ = 1, last_event_id_ = 0;
  // The last time the current object was seen: true centre and velocity [root], and the map
  // to the perceived root frame then.
  struct Seen {
    double time_s = 0.0;
    Eigen::Vector3d position = Eigen::Vector3d::Zero(), velocity = Eigen::Vector3d::Zero();
    Eigen::Isometry3d to_perceived = Eigen::Isometry3d::Identity();
  };
  std::optional<Seen> seen_;
  pps::TrueOffsets true_offsets_;
  std::map<std::string, int> per_part_presentations_, per_part_events_;
  std::map<std::string, int> unreachable_draws_;  // taxels given up per part (no clear path)
  std::map<std::string, int> per_motion_;
  std::unique_ptr<PresentationView> view_;           // set when the view can be checked
  std::map<std::string, int> per_part_out_of_view_;  // presentations not seen coming
  int paths_out_of_view_ = 0;                        // paths given up (view: require)
};

}  // namespace somasim::plugins
