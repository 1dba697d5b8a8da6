#pragma once
// The `true_offsets` port (contract shared by the stimulus sources that know the truth): per
// taxel, the mean over the skin contact events that touched it of (perceived D − true D) of the
// stimulus at the event. Perceived D: the perceived, noise-free stimulus against the taxel posed
// by the believed kinematics; true D: the true stimulus against the taxel posed by the true
// kinematics (somasim::pps::to_taxel_frame + compute_d_ttc). NaN for taxels never touched.
#include <map>
#include <string>
#include <vector>

#include "somasim/port_types.hpp"

namespace somasim::plugins {

class TrueOffsetTracker {
 public:
  /// Labels "part/id" of every taxel of every part of `truth` (parts in input order); keeps the
  /// sums of taxels already seen. Call whenever the taxel input may have changed.
  void update_layout(const SkinTaxels& truth, TaxelValues& out);
  /// Adds one event: `believed` may be null (the true poses are then used for both D).
  /// RunError when `believed` lacks the event's part or one of its taxels.
  void add_event(const ContactEvent& event, const SkinTaxels& truth, const SkinTaxels* believed,
                 const Stimulus& perceived, const Stimulus& true_stimulus, TaxelValues& out);
  /// Number of (event, taxel) samples so far.
  int samples() const { return samples_; }

 private:
  struct Sum {
    double sum = 0.0;
    int count = 0;
  };
  std::map<std::string, Sum> sums_;  // by label
  std::map<std::string, std::size_t> index_;
  int samples_ = 0;
};

}  // namespace somasim::plugins
