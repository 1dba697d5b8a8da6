#pragma once
// How far a run is, shown while it runs: a line rewritten in place on a terminal, or (stderr not
// a terminal: batch jobs, Slurm logs) one log line every `every_s` seconds of wall time.
#include <string>

#include <spdlog/logger.h>

#include "somasim/simulation.hpp"

namespace somasim {

/// One progress text, e.g. "sim 12.0/3600.0 s, objects presented 12/200, 41.2x real time,
/// ETA 110 s". The ETA extrapolates the wall time from the fraction done
/// (Simulation::progress_fraction): a node that ends the run early makes it shorter.
std::string progress_text(const Simulation& sim, double duration_s, double wall_s);

class ProgressReport {
 public:
  /// `line`: the in-place line when stderr is a terminal; `every_s` > 0: the log line's period
  /// when it is not (0: none).
  ProgressReport(bool line, double every_s, spdlog::logger& log);
  ProgressReport(const ProgressReport&) = delete;
  ProgressReport& operator=(const ProgressReport&) = delete;
  ~ProgressReport();
  void update(const Simulation& sim, double duration_s, double wall_s);

 private:
  bool line_ = false;
  double every_s_ = 0.0;
  spdlog::logger& log_;
  bool shown_ = false;
  double last_ = 0.0;
};

}  // namespace somasim
