#pragma once
// pps_learner: learns and evaluates the peripersonal-space maps of one body part's taxels.
#include <memory>
#include <optional>

#include "somasim/plugin.hpp"
#include "somasim/port_types.hpp"
#include "somasim/pps/body_part_learner.hpp"

namespace somasim::plugins {

class PpsLearner : public Plugin {
 public:
  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
  const SkinPart* find_part(NodeContext& ctx) const;
  void create_learner(NodeContext& ctx, const SkinPart& part);
  void learn_from_events(NodeContext& ctx);
  void update_activations();
  void report(NodeContext& ctx);

  pps::LearnerParams params_;
  std::string body_part_;
  std::string load_path_;
  std::string save_name_;
  bool learn_ = true;
  int min_samples_ = 0;
  std::vector<double> figure_taxels_;
  const Stimulus* stimulus_ = nullptr;
  const SkinTaxels* skin_ = nullptr;
  const ContactEvents* contacts_ = nullptr;
  TaxelValues* activations_ = nullptr;
  double* max_activation_ = nullptr;
  std::unique_ptr<pps::BodyPartLearner> learner_;
  std::uint64_t last_event_id_ = 0;
  std::size_t events_ = 0;
  std::vector<pps::TaxelPose> poses_;  // root frame, current tick
  std::vector<int> touched_;
  std::vector<std::size_t> snapshot_after_;  // event counts at which maps are drawn (Fig 9)
};

}  // namespace somasim::plugins
