#pragma once
// The reach_controller's evaluation (Vicente et al. 2016, section 4.3): per movement and frame,
// the estimation error (real vs estimated palm pose, with and without adaptation) and the
// reaching error (desired vs real, and desired vs estimated palm pose); statistics over the
// movements per frame, metrics at the end of the open loop and of the closed loop, figures like
// the paper's Figs 6–8 and a per-frame CSV.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace somasim::plugins {

/// Errors of one frame: position [mm] and orientation [deg].
struct FrameErrors {
  double estimation_mm = 0, estimation_deg = 0;      ///< real vs K(θ + β̂)
  double nominal_mm = 0, nominal_deg = 0;            ///< real vs K(θ)
  double reaching_mm = 0, reaching_deg = 0;          ///< desired vs real
  double reaching_est_mm = 0, reaching_est_deg = 0;  ///< desired vs K(θ + β̂)
};

struct MovementId {
  int movement = 0, target = 0, start = 0, repetition = 0;
};

class ReachReport {
 public:
  ReachReport(int open_loop_frames, int closed_loop_frames);

  /// Errors at `frame` (1 = first open-loop frame) of a movement.
  void add(const MovementId& id, int frame, const FrameErrors& errors);
  int movements_completed() const { return completed_; }
  void movement_done() { ++completed_; }

  /// The metrics of the file comment (means and sds over the completed movements).
  nlohmann::json metrics() const;
  void write_csv(const std::filesystem::path& file) const;
  /// The paper's Figs 6 (estimation error over frames, adapted vs nominal), 7 (real and
  /// estimated reaching error) and 8 (the same around the closed loop) as PNG files.
  void write_figures(const std::filesystem::path& estimation, const std::filesystem::path& reaching,
                     const std::filesystem::path& closed_loop, const std::string& title) const;

 private:
  struct Row {
    MovementId id;
    int frame = 0;
    FrameErrors e;
  };
  int open_frames_, closed_frames_;
  int completed_ = 0;
  std::vector<Row> rows_;
};

}  // namespace somasim::plugins
