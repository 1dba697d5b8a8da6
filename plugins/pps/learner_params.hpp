#pragma once
// The pps_learner's learning parameters as a config block (somasim/config.hpp) and their
// conversion to somasim::pps::LearnerParams. Defaults are the library's paper variant
// (Roncone et al. 2016, Learning peripersonal space representation through artificial skin for
// avoidance and reaching with whole body surface: LearnerParams::paper()); a parameter's
// description gives the released code's value where it differs.
#include "somasim/config.hpp"
#include "somasim/pps/body_part_learner.hpp"
#include "somasim/units.hpp"

namespace somasim::plugins {

struct LearnerConfig {
  pps::PpsModel model = paper().model;
  pps::GridSpec grid = paper().grid;  // d_min, d_max, d_bins, ttc_max, ttc_bins
  pps::TtcDefinition ttc = paper().ttc;
  double sigma_scale = paper().parzen.sigma_scale;
  pps::KernelAnchor kernel_anchor = paper().parzen.anchor;
  pps::RfShape rf_shape = paper().rf.shape;
  double rf_half_angle_deg = rad_to_deg(paper().rf.half_angle_rad);  // [deg]
  double rf_range = paper().rf.range_m;                              // [m]
  double buffer_horizon = paper().buffer.horizon_s;                  // [s]
  int contact_min_events = paper().contact.min_events;
  double contact_agreement = paper().contact.agreement_m;  // [m]
  double buffer_reset = paper().buffer.reset_after_s;      // [s]

  template <class V>
  void visit(V& v);
  /// The library's parameters (TTC from 0, angles in radians).
  pps::LearnerParams to_params() const;

 private:
  static pps::LearnerParams paper() { return pps::LearnerParams::paper(); }
};

}  // namespace somasim::plugins
