#pragma once
// What the PPS evaluator records of one presented object (one row of presentations.csv).
// Distances are true, signed (object surface to taxel centre; < 0: the object penetrates) [m];
// times are simulated [s].
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "somasim/pps/ports.hpp"
#include "somasim/robot/ports.hpp"

namespace somasim::plugins {

struct PresentationRecord {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  std::uint64_t id = 0;
  PresentationMotion motion = PresentationMotion::kApproach;
  std::string object, body_part, shape;  ///< shape: "sphere", "box", "cylinder" or "unknown"
  int taxel_id = -1;
  double speed = 0.0;                                        ///< [m/s]
  PresentationSight sight = PresentationSight::kNotChecked;  ///< could the cameras see it coming
  double start_s = 0.0, end_s = kNaN;     ///< presented over [start, end]; NaN: still open
  bool seen = false;                      ///< the object was found in the world at least once
  bool triggered = false;                 ///< a taxel of the aimed part went above threshold
  bool triggered_other_part = false;      ///< ... a taxel of another part did
  double trigger_time_s = kNaN;           ///< first trigger
  int trigger_taxel_id = -1;              ///< the most activated taxel at the first trigger
  double trigger_distance_m = kNaN;       ///< nearest taxel of the aimed part at that moment
  double min_distance_m = kNaN;           ///< to the nearest taxel of the aimed part
  double min_distance_any_part_m = kNaN;  ///< to the nearest taxel of any part
  double max_activation = 0.0;            ///< over the aimed part's taxels
  double max_speed = 0.0;                 ///< of the aimed part's controller [m/s] (if wired)
  bool skin_contact = false;              ///< a skin contact event on the aimed part
  bool skin_contact_any = false;          ///< ... on any part
  double contact_time_s = kNaN;           ///< first skin contact on the aimed part
  bool object_contact = false;            ///< the world reported object-robot contact

  bool open() const { return std::isnan(end_s); }
  /// Whether an event at time `t` happened while this object was presented.
  bool covers(double t) const { return t >= start_s - 1e-9 && (open() || t <= end_s + 1e-9); }
};

}  // namespace somasim::plugins
