#include "landscape_figure.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "somasim/figures/heatmap.hpp"
#include "somasim/pps/landscape_plot.hpp"

namespace somasim::plugins {

namespace {

std::optional<double> known_offset(const TaxelValues* offsets, const std::string& label) {
  if (!offsets) return std::nullopt;
  for (std::size_t i = 0; i < offsets->labels.size() && i < offsets->values.size(); ++i)
    if (offsets->labels[i] == label && std::isfinite(offsets->values[i])) return offsets->values[i];
  return std::nullopt;
}

/// "Taxel 3 of the left forearm: activation after 1234 samples, after learning" ("taxel" as the
/// part's name is the single-taxel experiment's: no part named then).
std::string landscape_title(std::string part, int id, std::uint64_t samples,
                            const std::string& when, bool distance_only) {
  std::replace(part.begin(), part.end(), '_', ' ');
  const std::string of_part = part == "taxel" ? "" : " of the " + part;
  return fmt::format("Taxel {}{}: activation from {} samples{}{}", id, of_part, samples, when,
                     distance_only ? " (distance only)" : "");
}

}  // namespace

void draw_landscapes(NodeContext& ctx, pps::BodyPartLearner& learner,
                     const std::vector<double>& taxel_ids, const std::string& suffix,
                     const TaxelValues* true_offsets) {
  std::vector<int> indices;
  if (taxel_ids.empty()) {
    for (int k = 0; k < static_cast<int>(learner.taxels().size()) && k < 4; ++k)
      indices.push_back(k);
  } else {
    for (double id : taxel_ids) {
      const int k = learner.index_of(static_cast<int>(id));
      if (k >= 0) indices.push_back(k);
    }
  }
  std::string when = suffix.empty() ? "" : ", " + suffix;
  std::replace(when.begin(), when.end(), '_', ' ');
  for (int k : indices) {
    pps::TaxelMap& map = learner.maps()[k];
    if (map.stale()) map.refresh();
    const int id = learner.taxels()[k].id;
    std::uint64_t samples = 0;
    for (std::size_t i = 0; i < map.pos().size(); ++i) samples += map.pos()[i] + map.neg()[i];
    pps::LandscapeOptions options;
    const bool distance_only = learner.params().model == pps::PpsModel::kDistanceOnly;
    // A distance-only map is constant along its placeholder TTC axis; no Fig 8 line.
    options.regression_line = !distance_only;
    options.true_offset_m =
        known_offset(true_offsets, learner.body_part() + "/" + std::to_string(id));
    options.title = landscape_title(learner.body_part(), id, samples, when, distance_only);
    const std::string file = fmt::format("landscape_{}_{}{}.png", learner.body_part(), id,
                                         suffix.empty() ? "" : "_" + suffix);
    figures::save_figure(figures::render_heatmap(pps::landscape_heatmap(map, options)),
                         ctx.figure_path(file));
  }
}

}  // namespace somasim::plugins
