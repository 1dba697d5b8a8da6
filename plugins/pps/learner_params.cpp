#include "learner_params.hpp"

#include <string>

namespace somasim::plugins {

template <class V>
void LearnerConfig::visit(V& v) {
  v.field("model", model)
      .doc(
          "d_ttc: (D, TTC) maps (paper); distance_only: maps over D alone, TTC ignored in "
          "learning and activation (the paper's S2 ablation: static and receding stimuli "
          "activate too)");
  v.block(grid);
  v.field("ttc", ttc)
      .doc(
          "signed: TTC = -|p|^2/(p.v), receding stimuli dropped (paper, robot code); "
          "unsigned: |p|/|v|, also behind the skin (authors' single-taxel data)");
  v.field("sigma_scale", sigma_scale)
      .range(0.05, 10)
      .doc("Parzen kernel sigma in bin widths (paper 1.0, released code 0.75)");
  v.field("kernel_anchor", kernel_anchor)
      .doc("Parzen kernels at bin centres (paper) or lower edges (released code)");
  v.field("rf_shape", rf_shape)
      .doc(
          "receptive field: cone around the normal, or the released code's cone mirrored "
          "below the skin plus a cylinder near it");
  v.field("rf_half_angle_deg", rf_half_angle_deg)
      .unit("deg")
      .range(0, 90)
      .doc("cone half-angle from the normal");
  v.field("rf_range", rf_range).unit("m").range(0, 2).doc("cone height along the normal");
  v.field("buffer_horizon", buffer_horizon)
      .unit("s")
      .range(0, 1e6)
      .doc("samples kept before a contact (paper 3 s, code 4 s); 0 keeps every sample");
  v.field("contact_min_events", contact_min_events)
      .range(1, 100000)
      .doc(
          "a taxel's contact offset estimate needs at least this many contact events that agree "
          "(fewer: no estimate, counted in contact_estimates_withheld)");
  v.field("contact_agreement", contact_agreement)
      .unit("m")
      .range(1e-4, 10)
      .doc(
          "contact events whose offset is farther than this from the taxel's median are "
          "outliers; an estimate needs more than half of them within it");
  v.field("buffer_reset", buffer_reset)
      .unit("s")
      .range(0, 1e6)
      .doc("the buffer is forgotten after this long without a stimulus");
}
template void LearnerConfig::visit(ConfigFields&);

pps::LearnerParams LearnerConfig::to_params() const {
  pps::LearnerParams p;
  p.grid = grid;
  p.ttc = ttc;
  p.parzen.sigma_scale = sigma_scale;
  p.parzen.anchor = kernel_anchor;
  p.rf.shape = rf_shape;
  p.rf.half_angle_rad = deg_to_rad(rf_half_angle_deg);
  p.rf.range_m = rf_range;
  p.buffer.horizon_s = buffer_horizon;
  p.buffer.reset_after_s = buffer_reset;
  p.model = model;
  p.contact.min_events = contact_min_events;
  p.contact.agreement_m = contact_agreement;
  return p;
}

}  // namespace somasim::plugins
