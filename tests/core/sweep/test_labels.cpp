// Sweep figure words: metric names as quantities with units, swept parameters from their docs.
#include <gtest/gtest.h>

#include <string>

#include "somasim/sweep/labels.hpp"

namespace somasim::sweep {
namespace {

TEST(Labels, MetricNamesReadAsQuantitiesWithUnits) {
  EXPECT_EQ(metric_label("offset_error_max_m"), "offset error max [m]");
  EXPECT_EQ(metric_label("estimation_error_mm"), "estimation error [mm]");
  EXPECT_EQ(metric_label("filter_step_ms"), "filter step [ms]");
  EXPECT_EQ(metric_label("speed_m_s"), "speed [m/s]");
  EXPECT_EQ(metric_label("estimation_error_deg"), "estimation error [deg]");
  EXPECT_EQ(metric_label("triggered_rate"), "triggered rate");
  EXPECT_EQ(metric_label("filter.frames"), "filter frames");
  EXPECT_EQ(metric_label("per_part.left_forearm.hits_mm"), "per part left forearm hits [mm]");
  // A name that is only a suffix stays a name.
  EXPECT_EQ(metric_label("_m"), " m");
  EXPECT_EQ(metric_label("m"), "m");
}

// Generated: every suffix on generated stems gives "stem words [unit]" and nothing is lost.
TEST(Labels, GeneratedNamesKeepTheirStemAndUnit) {
  const std::pair<const char*, const char*> suffixes[] = {
      {"_m", "m"}, {"_mm", "mm"}, {"_s", "s"}, {"_ms", "ms"}, {"_deg", "deg"}, {"_m_s", "m/s"}};
  for (const char* stem : {"a", "offset", "min_distance", "x_y_z", "trigger_distance"})
    for (const auto& [suffix, unit] : suffixes) {
      std::string words = stem;
      for (char& c : words)
        if (c == '_') c = ' ';
      EXPECT_EQ(metric_label(std::string(stem) + suffix), words + " [" + unit + "]")
          << stem << suffix;
    }
}

TEST(Labels, ParameterLabelsUseTheDocAndUnit) {
  EXPECT_EQ(parameter_label("nodes.thrower.params.offset", "start offset from the taxel", "m"),
            "offset [m]: start offset from the taxel");
  EXPECT_EQ(parameter_label("nodes.thrower.params.count", "", ""), "count");
  EXPECT_EQ(parameter_label("seed", "", ""), "seed");
  const std::string long_doc(200, 'x');
  // A long doc is cut at a word (or at 70 characters) and marked with an ellipsis.
  const std::string cut = parameter_label("a.b", "word " + long_doc, "s");
  EXPECT_EQ(cut, "b [s]: word …");
  EXPECT_EQ(parameter_label("a.b", long_doc, "s"), "b [s]: " + std::string(70, 'x') + " …");
}

}  // namespace
}  // namespace somasim::sweep
