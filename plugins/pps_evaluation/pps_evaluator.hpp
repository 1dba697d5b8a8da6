#pragma once
// pps_evaluator: scores PPS avoidance and reaching (issue 4; "Exploitation" in Roncone et al. 2016,
// Learning peripersonal space representation through artificial skin for avoidance and reaching
// with whole body surface) with the simulation's ground truth. For every object a stimulus source
// presents (`presentation`) it
// records whether a taxel of the aimed skin part went above `threshold` while the object was in
// the world (a trigger; for static and receding objects a false one), the true distance from the
// object's surface to the part's nearest taxel at the first trigger and its minimum over the
// presentation (exact for spheres, boxes and cylinders; see surface_distance.hpp), skin contact
// events on the aimed part and on any part, and object-robot contacts reported by the world.
// finish() reports the metrics (evaluation_report.hpp), writes one CSV row per presentation and
// draws Fig 10/11-style figures of chosen presentations.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <array>

#include "presentation_record.hpp"
#include "presentation_trace.hpp"
#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/port_types.hpp"
#include "somasim/pps/held_trigger.hpp"
#include "somasim/pps/part_activations.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/surface_distance.hpp"
#include "somasim/skin/ports.hpp"

namespace somasim::plugins {

class PpsEvaluator : public Plugin {
 public:
  static constexpr int kVelocityInputs = 4;  ///< velocity_1 .. velocity_4
  struct Config {
    double threshold = 0.4;
    double trigger_hold_s = 0.0;  // [s]
    double trigger_at_once_above = 1.0;
    std::vector<std::string> velocity_parts;
    std::vector<double> figure_presentations{1, 2, 3, 4};
    int figure_taxels = 3;
    OutputFile csv{"presentations.csv", {}};
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    In<Presentation> presentation;
    In<ObjectStates> objects;
    In<SkinTaxels> taxels;
    In<ContactEvents> contacts;
    In<TaxelValues> activations;
    OptionalIn<Contacts> world_contacts;
    OptionalIn<ObjectSpawns> spawns;
    std::array<OptionalIn<Eigen::Vector3d>, kVelocityInputs> velocity;  // velocity_1 ..
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
  void follow_presentation(NodeContext& ctx);
  void observe(NodeContext& ctx, PresentationRecord& r);
  void attribute_contacts();
  PresentationRecord* record_at(double t);
  const SkinPart* find_part(NodeContext& ctx, const std::string& name) const;
  robot::ObjectGeometry geometry_of(const std::string& object, std::size_t index) const;

  std::vector<std::string> velocity_parts_;  ///< part controlled by velocity_i ("" = none)
  std::string csv_name_;
  std::filesystem::path csv_path_;  // in the run folder, checked in configure()

  const Presentation* presentation_ = nullptr;
  const ObjectStates* objects_ = nullptr;
  const SkinTaxels* taxels_ = nullptr;
  const ContactEvents* contacts_ = nullptr;
  const Contacts* world_contacts_ = nullptr;  // optional
  const ObjectSpawns* spawns_ = nullptr;      // optional
  const TaxelValues* activations_ = nullptr;
  std::vector<const Eigen::Vector3d*> velocities_;  // per velocity input; null = unwired

  std::vector<PresentationRecord> records_;
  std::map<std::string, std::size_t> record_of_object_;
  std::map<std::string, robot::ObjectGeometry> geometries_;  ///< by object name, from `spawns`
  std::map<std::uint64_t, PresentationTrace> traces_;
  // The open presentation's crossings: of the aimed part, of any other part.
  pps::HeldTrigger aimed_trigger_, other_trigger_;
  std::map<std::string, pps::PartActivations> part_activations_;  ///< by aimed part
  std::uint64_t last_event_id_ = 0;
  double last_world_contact_s_ = -1.0;
  std::vector<double> distances_;  ///< scratch: per taxel of the aimed part
};

}  // namespace somasim::plugins
