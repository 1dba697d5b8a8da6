#pragma once
/// @file
/// Event-driven PPS learning for all taxels of one body part.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/pps/contact_evidence.hpp"
#include "somasim/pps/grid.hpp"
#include "somasim/pps/receptive_field.hpp"
#include "somasim/pps/stimulus.hpp"
#include "somasim/pps/stimulus_buffer.hpp"
#include "somasim/pps/taxel_map.hpp"

namespace somasim::pps {

/// Every learning parameter. Defaults: the paper text (centre anchors, sigma = 1 bin, TTC up to
/// 3 s, 3 s buffer, cone RF, signed TTC); code() gives the released robot code's values.
struct LearnerParams {
  GridSpec grid = GridSpec::paper();
  ParzenSpec parzen = ParzenSpec::paper();
  ReceptiveField rf = ReceptiveField::paper();
  TtcDefinition ttc = TtcDefinition::kSigned;
  BufferSpec buffer = BufferSpec::paper();
  /// kDistanceOnly: 1-D maps over D (grid's D axis only); every in-RF sample with D in range
  /// counts (receding or static ones too), and activation() ignores the velocity.
  PpsModel model = PpsModel::kDTtc;
  /// When the contact offset estimator reports an estimate (contact_evidence.hpp).
  ContactEstimateSpec contact;

  static LearnerParams paper() { return LearnerParams{}; }
  static LearnerParams code() {
    return LearnerParams{GridSpec::code(),
                         ParzenSpec::code(),
                         ReceptiveField::code(),
                         TtcDefinition::kSigned,
                         BufferSpec::code(),
                         PpsModel::kDTtc,
                         {}};
  }
};

/// A taxel of a body part: id and pose in the link frame [m].
struct TaxelInfo {
  int id = 0;
  TaxelPose pose_link;
};

/// Where the skin was touched: centre of pressure [m] and outward unit normal there, both in
/// the frame of the part's link.
struct SkinTouch {
  Eigen::Vector3d point_link;
  Eigen::Vector3d normal_link;
};

/// What one contact event taught.
struct LearningStats {
  std::size_t buffered_samples = 0;  ///< samples in the buffer at the event
  std::size_t touched_taxels = 0;    ///< taxels marked touched (known ids only)
  std::size_t in_rf = 0;             ///< (sample, taxel) pairs inside the RF
  std::size_t invalid_ttc = 0;       ///< ... of which TTC undefined (e.g. receding): ignored
  std::size_t out_of_range = 0;      ///< ... of which (D, TTC) outside the grid: ignored
  std::size_t positives = 0;         ///< counts added to pos
  std::size_t negatives = 0;         ///< counts added to neg
  std::size_t behind_skin = 0;       ///< counted samples with D < 0
};

class BodyPartLearner {
 public:
  BodyPartLearner(std::string body_part, std::vector<TaxelInfo> taxels,
                  const LearnerParams& params);

  const std::string& body_part() const { return body_part_; }
  const LearnerParams& params() const { return params_; }
  const std::vector<TaxelInfo>& taxels() const { return taxels_; }
  /// The maps' grid: params().grid, or distance_only_grid(params().grid) for the distance-only
  /// model.
  const GridSpec& map_grid() const { return map_grid_; }
  const std::vector<TaxelMap>& maps() const { return maps_; }
  std::vector<TaxelMap>& maps() { return maps_; }
  /// Index of taxel `id`, or -1.
  int index_of(int id) const;

  StimulusBuffer& buffer() { return buffer_; }
  const StimulusBuffer& buffer() const { return buffer_; }
  /// Buffers a stimulus sample (root frame).
  void push_stimulus(const StimulusSample& s) { buffer_.push(s); }

  /// Contact event. `taxels_root[k]` is the pose of taxel k (same order as taxels()) in the root
  /// frame at contact time; `touched_ids` the ids of the touched taxels (unknown ids are
  /// ignored). Every buffered sample inside a taxel's RF with valid, in-range (D, TTC) adds 1 to
  /// pos (touched) or neg (untouched). The buffer is then cleared. InputError if the pose count
  /// differs from the taxel count. No allocation after the first event.
  LearningStats on_contact(std::span<const TaxelPose> taxels_root,
                           std::span<const int> touched_ids);
  /// Same, with every taxel posed by the link's pose in the root frame (root <- link).
  LearningStats on_contact(const Eigen::Isometry3d& root_from_link,
                           std::span<const int> touched_ids);

  /// The `contact` offset estimator's evidence. With the centre of pressure `touch`: for the
  /// touched taxel nearest it (nearest_point), the perceived D of the stimulus minus the D the
  /// skin itself implies, both where the object was kOffsetClearance outside that taxel on its
  /// way in — the moment the truth is taken at (true_offsets.hpp). The skin's D is that of a
  /// stimulus of the perceived radius resting on the skin at `touch` (link frame, so free of
  /// kinematic error), moved back along the perceived velocity (rotated into the link frame by
  /// the believed link pose, fitted to the taxels); the perceived stimulus is interpolated from
  /// the buffered samples at that time. Without `touch`: the perceived D at `touch_time_s`
  /// for every touched taxel (the contact taken at the taxel centres).
  ///
  /// Call before on_contact() (which clears the buffer); taxel poses as for on_contact().
  /// Nothing is recorded without a buffered sample.
  void record_contact_offset(std::span<const TaxelPose> taxels_root,
                             std::span<const int> touched_ids, double touch_time_s,
                             const std::optional<SkinTouch>& touch = std::nullopt);
  /// Sum of the recorded contact D of taxel index k [m] and their count.
  double contact_d_sum(int k) const { return contact_.sum(static_cast<std::size_t>(k)); }
  std::uint32_t contact_count(int k) const { return contact_.count(static_cast<std::size_t>(k)); }
  /// Restores recorded evidence (e.g. from a learned file).
  void set_contact_offset(int k, double d_sum, std::uint32_t count) {
    contact_.restore(static_cast<std::size_t>(k), d_sum, count);
  }
  /// The estimate of taxel index k [m]: the mean of its contact D values that agree with their
  /// median (params().contact); nullopt when there is too little or disagreeing evidence.
  std::optional<double> contact_offset(int k) const;
  /// Whether taxel index k has an estimate, and why not.
  ContactEvidence contact_evidence(int k) const {
    return contact_.state(static_cast<std::size_t>(k), params_.contact);
  }

  /// Totals over all events so far.
  const LearningStats& totals() const { return totals_; }

  /// Activation of taxel index k for a stimulus in the root frame, with the taxel at
  /// `taxel_root` (0 outside the RF or, for the (D, TTC) model, when TTC is undefined, e.g. for
  /// a receding or static stimulus with the signed TTC; the distance-only model uses D only).
  double activation(int k, const TaxelPose& taxel_root, const Stimulus& s) const;

 private:
  std::string body_part_;
  LearnerParams params_;
  std::vector<TaxelInfo> taxels_;
  std::vector<TaxelMap> maps_;
  StimulusBuffer buffer_;
  PreparedRf rf_;
  GridSpec map_grid_;
  double query_ttc_ = 0.0;  // distance-only: the TTC at which maps are queried
  LearningStats totals_;
  std::vector<TaxelPose> scratch_poses_;
  std::vector<std::uint8_t> touched_;
  Stimulus perceived_at(double t) const;
  ContactEvidenceLog contact_;
};

}  // namespace somasim::pps
