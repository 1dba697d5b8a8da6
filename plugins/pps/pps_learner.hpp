#pragma once
// pps_learner: learns and evaluates the peripersonal-space maps of the taxels of one or several
// body parts (one pps::BodyPartLearner per part).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "learner_params.hpp"
#include "learner_part.hpp"
#include "offset_groups.hpp"
#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/port_types.hpp"
#include "somasim/pps/body_part_learner.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/skin/ports.hpp"

namespace somasim::plugins {

class PpsLearner : public Plugin {
 public:
  struct Config {
    std::vector<std::string> body_part{"taxel"};
    LearnerConfig learning;
    bool learn = true;
    InputFile load;
    OutputFile save{"pps_map.json", {}};
    std::vector<double> figure_taxels;
    std::vector<double> snapshot_events;
    int min_samples = 50;
    std::string offset_groups;
    template <class V>
    void visit(V& v);
    void validate(ConfigChecks& checks) const;  // cross-field checks
  };
  struct Ports {
    In<pps::Stimulus> stimulus;
    In<SkinTaxels> taxels;
    OptionalIn<ContactEvents> contacts;
    OptionalIn<TaxelValues> true_offsets;
    Out<TaxelValues> activations;
    Out<double> max_activation;
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
  void parse_body_parts();
  void load(NodeContext& ctx, const std::filesystem::path& file);
  void bind_parts(NodeContext& ctx);
  void add_geometry(LearnerPart& p, const SkinPart& part);
  std::vector<double> snapshot_taxels(NodeContext& ctx, const LearnerPart& p) const;
  static constexpr std::size_t kSnapshotTaxels = 4;
  void check_figure_taxels(NodeContext& ctx) const;
  const SkinPart& input_part(NodeContext& ctx, LearnerPart& part) const;
  void learn_from_events(NodeContext& ctx);
  void update_activations();

  pps::LearnerParams params_;
  std::string load_path_;
  std::string save_name_;
  std::filesystem::path save_path_;  // in the run folder, checked in configure()
  std::vector<OffsetGroup> offset_groups_;
  const pps::Stimulus* stimulus_ = nullptr;
  const SkinTaxels* skin_ = nullptr;
  const ContactEvents* contacts_ = nullptr;
  const TaxelValues* true_offsets_ = nullptr;
  TaxelValues* activations_ = nullptr;
  double* max_activation_ = nullptr;
  std::vector<LearnerPart> parts_;  // in the order of the body_part parameter
  bool bound_ = false;              // parts found in the taxels input, learners created
  std::uint64_t last_event_id_ = 0;
  std::vector<std::size_t> snapshot_after_;  // per-part event counts at which maps are drawn
};

}  // namespace somasim::plugins
