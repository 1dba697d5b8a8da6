#pragma once
/// @file
/// The `contact` offset estimator's evidence per taxel and its estimate: the perceived D minus
/// the D the skin implies, one value [m] per contact event (body_part_learner.hpp says how each
/// is measured). One wrong value — a tracker's false fix at a touch, a contact read off the
/// wrong taxel — must not become an absurd estimate, so the estimate is the mean of the values
/// that agree with their median, and a taxel whose values are too few or disagree reports none.
#include <cstdint>
#include <optional>
#include <vector>

namespace somasim::pps {

struct ContactEstimateSpec {
  /// Fewer agreeing values than this: no estimate (too little evidence).
  int min_events = 2;
  /// Values farther than this from the median [m] are outliers; an estimate needs more than
  /// half of the values within it.
  double agreement_m = 0.02;
};

/// Why a taxel has no estimate.
enum class ContactEvidence : std::uint8_t {
  kEstimated,    ///< an estimate
  kNone,         ///< never touched
  kTooFew,       ///< fewer than min_events agreeing values
  kDisagreeing,  ///< no majority of values within agreement_m of their median
};

class ContactEvidenceLog {
 public:
  void resize(std::size_t taxels);
  /// Adds one value [m] for taxel k.
  void add(std::size_t k, double d);
  /// Restores evidence saved as a sum and a count (a learned file keeps no single values: the
  /// estimate is then their mean when count >= min_events, without the outlier test).
  void restore(std::size_t k, double sum, std::uint32_t count);

  double sum(std::size_t k) const { return sum_[k]; }
  std::uint32_t count(std::size_t k) const { return count_[k]; }
  ContactEvidence state(std::size_t k, const ContactEstimateSpec& spec) const;
  /// The estimate of taxel k [m], nullopt unless state() is kEstimated.
  std::optional<double> estimate(std::size_t k, const ContactEstimateSpec& spec) const;

 private:
  struct Robust {
    ContactEvidence state = ContactEvidence::kNone;
    double value = 0.0;
  };
  Robust evaluate(std::size_t k, const ContactEstimateSpec& spec) const;

  std::vector<std::vector<double>> values_;  // this run's values (empty after restore())
  std::vector<double> sum_;
  std::vector<std::uint32_t> count_;
};

}  // namespace somasim::pps
