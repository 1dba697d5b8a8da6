#pragma once
/// @file
/// The activations of one skin part, picked from a TaxelValues that may carry several parts
/// (labels "part/id", as pps_learner writes them) or, unlabelled, exactly one part's values.
/// Shared by pps_controller and pps_evaluator.
#include <span>
#include <string>
#include <vector>

#include "somasim/skin/ports.hpp"

namespace somasim::pps {

class PartActivations {
 public:
  /// The values of `part`'s taxels in the order of part.taxel_ids. Labelled input: each taxel's
  /// value is the one labelled "<part>/<id>" (other parts' values are ignored); unlabelled
  /// input: one value per taxel, in order. Empty input (nothing computed yet): an empty span.
  /// RunError, prefixed with `who` (the node name), when the input does not fit the part.
  std::span<const double> select(const TaxelValues& input, const SkinPart& part,
                                 const std::string& who);

 private:
  void build_index(const TaxelValues& input, const SkinPart& part, const std::string& who);

  std::vector<std::string> labels_;  ///< the labels index_ was built for
  std::string part_;
  std::vector<int> ids_;
  std::vector<std::size_t> index_;  ///< input position of each taxel of the part
  std::vector<double> values_;
};

}  // namespace somasim::pps
