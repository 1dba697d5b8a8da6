// Validation on a real iCub skin recording (robotology/peripersonal-space's dataSetPlayer log of
// /skinManager/skin_events:o, Oct 2014) and the iCub's taxel positions files (icub-main
// skinGui), both in the shared data directory ($SOMASIM_SHARED_DIR, default
// <source dir>/../shared); skipped when absent.
//
// Every contact of the log is decoded; on the parts whose positions file matches the robot that
// recorded it, every touched taxel exists in the layout and the contact's geometric centre
// (computed by the robot's skinManager from its positions file) equals the mean of the touched
// taxels' positions in somasim's layout: the events land on the right taxels.
#include <cstdlib>
#include <filesystem>
#include <map>

#include <gtest/gtest.h>

#include "somasim/recordings/datadumper_log.hpp"
#include "somasim/recordings/skin_contact_list.hpp"
#include "somasim/skin/layout_file.hpp"

using namespace somasim;
using namespace somasim::recordings;
namespace fs = std::filesystem;

namespace {

fs::path shared_dir() {
  if (const char* e = std::getenv("SOMASIM_SHARED_DIR"); e && *e) return e;
  return fs::path(SOMASIM_SOURCE_DIR) / ".." / "shared";
}

fs::path skin_log() {
  return shared_dir() / "pps-data" / "robotology-peripersonal-space" / "app" / "conf" /
         "dataSetPlayer" / "rightleftforearmshands" / "rightleftforearmshands" / "data.log";
}

fs::path positions(const std::string& file) {
  return shared_dir() / "pps-data" / "robotology-icub-main" / "app" / "skinGui" / "conf" /
         "positions" / file;
}

struct PartCheck {
  std::size_t contacts = 0, missing_taxels = 0;
  double worst_centre_m = 0.0;
};

// Decodes every contact on `skin_part` and compares it with the layout of `file`.
PartCheck check_part(const DatadumperLog& log, int skin_part, const std::string& file) {
  const skin::SkinLayout layout = skin::load_layout_file(positions(file), "part", 0);
  std::map<int, std::size_t> index;
  for (std::size_t i = 0; i < layout.ids.size(); ++i) index[layout.ids[i]] = i;
  PartCheck out;
  for (const DumpEntry& e : log.entries)
    for (const SkinContactRecord& c : decode_skin_contact_list(parse_bottle(e.content))) {
      if (c.skin_part != skin_part) continue;
      ++out.contacts;
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      std::size_t found = 0;
      for (int t : c.taxels) {
        const auto it = index.find(t);
        if (it == index.end()) {
          ++out.missing_taxels;
          continue;
        }
        sum += layout.positions[it->second];
        ++found;
      }
      if (found == c.taxels.size() && found > 0)
        out.worst_centre_m = std::max(
            out.worst_centre_m, (sum / static_cast<double>(found) - c.geometric_centre).norm());
    }
  return out;
}

}  // namespace

TEST(RealSkinLog, ParsesAndLandsOnTheIcubLayout) {
  if (!fs::exists(skin_log())) GTEST_SKIP() << "shared data absent: " << skin_log();
  const DatadumperLog log = read_datadumper_log(skin_log());
  EXPECT_EQ(log.entries.size(), 3479u);
  EXPECT_EQ(log.ports, std::vector<std::string>{"/skinManager/skin_events:o"});
  EXPECT_TRUE(log.timeline.gaps.empty());
  EXPECT_NEAR(1.0 / log.timeline.median_step_s, 50.0, 0.5);  // the skin's 50 Hz

  std::map<int, std::size_t> per_part;
  for (const DumpEntry& e : log.entries)
    for (const SkinContactRecord& c : decode_skin_contact_list(parse_bottle(e.content)))
      ++per_part[c.skin_part];
  EXPECT_EQ(per_part, (std::map<int, std::size_t>{
                          {1, 381}, {2, 1045}, {4, 277}, {5, 924}, {6, 8}, {7, 127}}));

  // The forearms of 2014 (the "mesh" V1 positions) and the right hand (V2.1): exact.
  for (const auto& [part, file] : std::map<int, std::string>{{2, "left_forearm_mesh.txt"},
                                                             {5, "right_forearm_mesh.txt"},
                                                             {4, "right_hand_V2_1.txt"}}) {
    const PartCheck c = check_part(log, part, file);
    EXPECT_EQ(c.contacts, per_part[part]) << file;
    EXPECT_EQ(c.missing_taxels, 0u) << file;
    EXPECT_LT(c.worst_centre_m, 0.0006) << file;  // the log's 6 decimals of 3 means
  }
  // The V2 forearm files are a later skin: the same ids land elsewhere or nowhere.
  const PartCheck v2 = check_part(log, 2, "left_forearm_V2.txt");
  EXPECT_GT(v2.missing_taxels, 100u);
}
