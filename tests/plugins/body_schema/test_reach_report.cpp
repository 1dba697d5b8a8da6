// The reach_controller's report: metrics at the end of the open loop and of the closed loop
// (means and sds over the movements that reached that frame, null where none did), the gains
// as ratios of those means, the per-frame CSV, and the three figures written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "reach_report.hpp"

using somasim::plugins::FrameErrors;
using somasim::plugins::MovementId;
using somasim::plugins::ReachReport;

namespace {

// Movement m (1, 2, 3) has errors m × base at every frame, and at the last open-loop frame
// reaching errors that the closed loop halves.
FrameErrors errors(int m, bool closed) {
  FrameErrors e;
  e.estimation_mm = 2.0 * m, e.estimation_deg = 1.0 * m;
  e.nominal_mm = 6.0 * m, e.nominal_deg = 2.0 * m;
  e.reaching_mm = (closed ? 5.0 : 10.0) * m, e.reaching_deg = (closed ? 1.0 : 4.0) * m;
  e.reaching_est_mm = 3.0 * m, e.reaching_est_deg = 0.5 * m;
  return e;
}

ReachReport three_movements(int closed_movements) {
  ReachReport r(4, 2);  // frames 1-4 open loop, 5-6 closed loop
  for (int m = 1; m <= 3; ++m) {
    const MovementId id{m, m - 1, 0, 0};
    const int last = m <= closed_movements ? 6 : 4;
    for (int frame = 1; frame <= last; ++frame) r.add(id, frame, errors(m, frame > 4));
    r.movement_done();
  }
  return r;
}

}  // namespace

TEST(ReachReport, MetricsAtTheEndOfEachLoop) {
  const nlohmann::json m = three_movements(3).metrics();
  EXPECT_EQ(m["reach_movements"], 3);
  EXPECT_EQ(m["reach_movements_at_frame_4"], 3);
  EXPECT_DOUBLE_EQ(m["estimation_error_mm"].get<double>(), 4.0);  // mean of 2, 4, 6
  EXPECT_DOUBLE_EQ(m["estimation_error_mm_sd"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(m["estimation_error_nominal_deg"].get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(m["reaching_error_open_loop_mm"].get<double>(), 20.0);
  EXPECT_DOUBLE_EQ(m["reaching_error_closed_loop_mm"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(m["reaching_error_estimated_closed_loop_deg"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(m["estimation_gain_position"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(m["estimation_gain_orientation"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(m["closed_loop_gain_position"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(m["closed_loop_gain_orientation"].get<double>(), 4.0);
}

TEST(ReachReport, ClosedLoopOfFewerMovementsAndNoneAtAll) {
  const nlohmann::json some = three_movements(1).metrics();
  EXPECT_DOUBLE_EQ(some["reaching_error_closed_loop_mm"].get<double>(), 5.0);  // movement 1 only
  EXPECT_EQ(some["reaching_error_closed_loop_mm_sd"].get<double>(), 0.0);
  const nlohmann::json none = three_movements(0).metrics();
  EXPECT_TRUE(none["reaching_error_closed_loop_mm"].is_null());
  EXPECT_TRUE(none["closed_loop_gain_position"].is_null());
  EXPECT_TRUE(none["estimation_error_final_mm"].is_null());
  EXPECT_FALSE(none["estimation_gain_position"].is_null());
}

TEST(ReachReport, CsvAndFigures) {
  const auto dir = std::filesystem::temp_directory_path() / "somasim_test_reach_report";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const ReachReport r = three_movements(2);
  r.write_csv(dir / "reach.csv");
  std::ifstream in(dir / "reach.csv");
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("movement,target,start,repetition,frame,", 0), 0u);
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 6 + 6 + 4);
  r.write_figures(dir / "a.png", dir / "b.png", dir / "c.png", "test");
  for (const char* f : {"a.png", "b.png", "c.png"})
    EXPECT_GT(std::filesystem::file_size(dir / f), 1000u) << f;
  std::filesystem::remove_all(dir);
}
