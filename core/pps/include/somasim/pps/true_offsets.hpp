#pragma once
/// @file
/// The offset each taxel SHOULD show in its learned PPS map (shared contract 2), known here
/// because the simulation knows the truth: for every skin contact event,
///   perceived D − true D,
/// perceived D = D of the perceived, noise-free stimulus w.r.t. the taxel posed by the BELIEVED
/// kinematics; true D = D of the true stimulus w.r.t. the taxel posed by the TRUE kinematics
/// (pps::to_taxel_frame + pps::compute_d_ttc, radius = the stimulus radius); the value of a taxel
/// is the mean over its events, NaN while it was never touched.
///
/// Which taxel: when the event carries the skin's centre of pressure, only the touched taxel
/// nearest it (pps::nearest_point); else every touched taxel.
///
/// When: with a `clearance` (objects on straight paths: pps::kOffsetClearance), both stimuli
/// are moved back along their velocities to where the true one was that far outside the
/// taxel's true skin plane — at the contact itself D = sign(p_z)|p| is discontinuous for a
/// taxel displaced sideways, and the offset's sign would be decided by noise. Without one, at
/// the stimuli given.
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "somasim/pps/ports.hpp"
#include "somasim/pps/stimulus.hpp"
#include "somasim/skin/ports.hpp"

namespace somasim::pps {

/// One instant of a stimulus path: the perceived and the true stimulus at `time_s` [s].
struct PathSample {
  double time_s = 0.0;
  Stimulus perceived, truth;
};

class TrueOffsets {
 public:
  /// Adopts the taxels of `true_taxels` (labels "part/id", parts in input order); sums are kept
  /// while the layout stays the same and reset when it changes.
  void sync_layout(const SkinTaxels& true_taxels);
  /// Adds one contact event (its body part's touched taxels). `believed_taxels` must hold the
  /// event's part with the same ids (RunError otherwise; pass `true_taxels` when the robot's
  /// kinematics are exact). Returns the taxels counted.
  int add_event(const ContactEvent& event, const SkinTaxels& true_taxels,
                const SkinTaxels& believed_taxels, const Stimulus& perceived, const Stimulus& truth,
                std::optional<double> clearance = std::nullopt);
  /// Same for a stimulus on a curved path (a fingertip): the stimuli are taken from `path`
  /// (time order, ending at the event) where the true one was `clearance` outside the credited
  /// taxel's true skin plane, interpolated between samples; a taxel whose plane the path never
  /// was that far outside of is not counted.
  int add_event_on_path(const ContactEvent& event, const SkinTaxels& true_taxels,
                        const SkinTaxels& believed_taxels, std::span<const PathSample> path,
                        double clearance);
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
