// Validation against the real iCub learned file in the shared data directory (skipped when
// absent). Directory: $SOMASIM_SHARED_DIR, default <source dir>/../shared.
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include "reference_counts.hpp"
#include "somasim/pps/ini_import.hpp"

using namespace somasim::pps;

namespace {
std::filesystem::path shared_dir() {
  if (const char* e = std::getenv("SOMASIM_SHARED_DIR"); e && *e) return e;
  return std::filesystem::path(SOMASIM_SOURCE_DIR) / ".." / "shared";
}
}  // namespace

TEST(PpsReferenceValidation, LearnedIniActivations) {
  const auto file = shared_dir() / "pps-data" / "robotology-peripersonal-space" / "app" / "conf" /
                    "taxelsFiles" / "forearmSkinV1" / "taxels2D_learned_rightHandLeftForearm.ini";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "shared data absent: " << file;
  const auto states = import_taxels2d_ini(file.string());
  ASSERT_EQ(states.size(), 2u);
  int checked = 0;
  for (const LearnedState& s : states) {
    EXPECT_EQ(s.grid, GridSpec::code());
    for (const LearnedTaxel& t : s.taxels) {
      const std::array<double, 6>* ref = nullptr;
      if (s.body_part == "l_forearm" && t.id == 3) ref = &pps_ref::kTaxel3Act;
      if (s.body_part == "r_hand" && t.id == 101) ref = &pps_ref::kTaxel101Act;
      if (!ref) continue;
      const TaxelMap m = make_map(s, t);
      for (std::size_t k = 0; k < ref->size(); ++k) {
        const auto [d, ttc] = pps_ref::kPoints[k];
        EXPECT_NEAR(m.activation(d, ttc), (*ref)[k], 0.005)
            << s.body_part << " taxel " << t.id << " at (" << d << ", " << ttc << ")";
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 12);
}
