#include "progress_report.hpp"

#include <unistd.h>

#include <fmt/format.h>

namespace somasim {

std::string progress_text(const Simulation& sim, double duration_s, double wall_s) {
  const double sim_t = sim.time_s();
  std::string text = fmt::format("sim {:.1f}/{:.1f} s", sim_t, duration_s);
  if (const auto p = sim.furthest_progress())
    text += fmt::format(", {} {}/{}", p->what, p->done, p->total);
  const double rtf = wall_s > 0 ? sim_t / wall_s : 0.0;
  text += fmt::format(", {:.1f}x real time", rtf);
  const double f = sim.progress_fraction();
  if (f > 0) text += fmt::format(", ETA {:.0f} s", wall_s * (1.0 - f) / f);
  return text;
}

ProgressReport::ProgressReport(bool line, double every_s, spdlog::logger& log) : log_(log) {
  if (isatty(STDERR_FILENO))
    line_ = line;
  else
    every_s_ = every_s;
}

void ProgressReport::update(const Simulation& sim, double duration_s, double wall_s) {
  if (line_) {
    if (wall_s - last_ < 0.5) return;
    last_ = wall_s;
    fmt::print(stderr, "\r  {}   ", progress_text(sim, duration_s, wall_s));
    shown_ = true;
  } else if (every_s_ > 0 && wall_s - last_ >= every_s_) {
    last_ = wall_s;
    log_.info("progress: {}", progress_text(sim, duration_s, wall_s));
  }
}

ProgressReport::~ProgressReport() {
  if (shown_) fmt::print(stderr, "\n");
}

}  // namespace somasim
