#pragma once
/// @file
/// The offset each taxel SHOULD show in its learned PPS map (shared contract 2), known here
/// because the simulation knows the truth: for every skin contact event that touched a taxel,
///   perceived D − true D,
/// perceived D = D of the perceived, noise-free stimulus w.r.t. the taxel posed by the BELIEVED
/// kinematics; true D = D of the true stimulus w.r.t. the taxel posed by the TRUE kinematics
/// (pps::to_taxel_frame + pps::compute_d_ttc, radius = the stimulus radius); the value of a taxel
/// is the mean over its events, NaN while it was never touched.
///
/// "At the event" means as the object reached the skin: a skin reports a contact up to one of
/// its periods late, when the object already presses into it, and D = sign(p_z)|p| of a touched
/// taxel BESIDE the contact point (p_z ≈ 0, |p| = its distance from the contact point) then flips
/// to −|p|. So the source moves the true object back along its path to the last instant it was
/// outside every touched taxel's skin plane (time_since_reaching_skin).
#include <map>
#include <string>
#include <vector>

#include "somasim/pps/ports.hpp"
#include "somasim/pps/stimulus.hpp"
#include "somasim/skin/ports.hpp"

namespace somasim::pps {

/// How long [s] before `truth` (the true stimulus at the event, root frame) the object was
/// last at least `clearance` [m] outside (p_z ≥ clearance, true kinematics) every taxel the
/// event touched that it moves toward; 0 when it already is, at most `max_s`.
double time_since_reaching_skin(const ContactEvent& event, const SkinTaxels& true_taxels,
                                const Stimulus& truth, double clearance = 1e-4, double max_s = 0.1);

class TrueOffsets {
 public:
  /// Adopts the taxels of `true_taxels` (labels "part/id", parts in input order); sums are kept
  /// while the layout stays the same and reset when it changes.
  void sync_layout(const SkinTaxels& true_taxels);
  /// Adds one contact event (its body part's touched taxels). `believed_taxels` must hold the
  /// event's part with the same ids (RunError otherwise; pass `true_taxels` when the robot's
  /// kinematics are exact). Returns the taxels counted.
  int add_event(const ContactEvent& event, const SkinTaxels& true_taxels,
                const SkinTaxels& believed_taxels, const Stimulus& perceived,
                const Stimulus& truth);
  /// Labels and current means (NaN for taxels never touched).
  void write(TaxelValues& out) const;
  /// Per part: mean of the per-taxel means over its touched taxels, and their count.
  std::map<std::string, std::pair<double, int>> part_means() const;

 private:
  std::vector<std::pair<std::string, std::vector<int>>> layout_;  // parts and their taxel ids
  std::vector<std::string> labels_, part_of_;
  std::map<std::string, std::size_t> index_;  // label -> slot
  std::vector<double> sum_;
  std::vector<int> count_;
};

}  // namespace somasim::pps
