#include "learner_params.hpp"

#include <cmath>
#include "somasim/units.hpp"

namespace somasim::plugins {

void declare_learner_params(PluginSpec& s) {
  s.add_string("model")
      .defaults(std::string("d_ttc"))
      .one_of({"d_ttc", "distance_only"})
      .describe(
          "d_ttc: (D, TTC) maps (paper); distance_only: maps over D alone, TTC ignored in "
          "learning and activation (the paper's S2 ablation: static and receding stimuli "
          "activate too)");
  s.add_double("d_min").unit_is("m").defaults(-0.10).range(-1, 1).describe(
      "lower edge of the D range");
  s.add_double("d_max").unit_is("m").defaults(0.20).range(-1, 1).describe(
      "upper edge of the D range");
  s.add_int("d_bins").defaults(std::int64_t{8}).range(1, 32).describe("number of D bins");
  s.add_double("ttc_max").unit_is("s").defaults(3.0).range(0.01, 100).describe(
      "upper edge of the TTC range (paper text 3 s; released robot code 1.2 s)");
  s.add_int("ttc_bins").defaults(std::int64_t{4}).range(1, 32).describe("number of TTC bins");
  s.add_string("ttc")
      .defaults(std::string("signed"))
      .one_of({"signed", "unsigned"})
      .describe(
          "signed: TTC = -|p|^2/(p.v), receding stimuli dropped (paper, robot code); "
          "unsigned: |p|/|v|, also behind the skin (authors' single-taxel data)");
  s.add_double("sigma_scale")
      .defaults(1.0)
      .range(0.05, 10)
      .describe("Parzen kernel sigma in bin widths (paper 1.0, released code 0.75)");
  s.add_string("kernel_anchor")
      .defaults(std::string("centre"))
      .one_of({"centre", "lower_edge"})
      .describe("Parzen kernels at bin centres (paper) or lower edges (released code)");
  s.add_string("rf_shape")
      .defaults(std::string("cone"))
      .one_of({"cone", "cone_mirrored_cylinder"})
      .describe(
          "receptive field: cone around the normal, or the released code's cone mirrored "
          "below the skin plus a cylinder near it");
  s.add_double("rf_half_angle_deg")
      .unit_is("deg")
      .defaults(50.0)
      .range(0, 90)
      .describe("cone half-angle from the normal");
  s.add_double("rf_range")
      .unit_is("m")
      .defaults(0.20)
      .range(0, 2)
      .describe("cone height along the normal");
  s.add_double("buffer_horizon")
      .unit_is("s")
      .defaults(3.0)
      .range(0, 1e6)
      .describe("samples kept before a contact (paper 3 s, code 4 s); 0 keeps every sample");
  s.add_int("contact_min_events")
      .defaults(std::int64_t{2})
      .range(1, 100000)
      .describe(
          "a taxel's contact offset estimate needs at least this many contact events that agree "
          "(fewer: no estimate, counted in contact_estimates_withheld)");
  s.add_double("contact_agreement")
      .unit_is("m")
      .defaults(0.02)
      .range(1e-4, 10)
      .describe(
          "contact events whose offset is farther than this from the taxel's median are "
          "outliers; an estimate needs more than half of them within it");
  s.add_double("buffer_reset")
      .unit_is("s")
      .defaults(2.0)
      .range(0, 1e6)
      .describe("the buffer is forgotten after this long without a stimulus");
}

pps::LearnerParams read_learner_params(const NodeContext& ctx) {
  pps::LearnerParams p;
  p.grid.d_min = ctx.param<double>("d_min");
  p.grid.d_max = ctx.param<double>("d_max");
  p.grid.d_bins = ctx.param<int>("d_bins");
  p.grid.ttc_min = 0.0;
  p.grid.ttc_max = ctx.param<double>("ttc_max");
  p.grid.ttc_bins = ctx.param<int>("ttc_bins");
  if (p.grid.d_max <= p.grid.d_min)
    ctx.param_error("d_max", "must be greater than d_min (" + std::to_string(p.grid.d_min) + ")");
  p.ttc = ctx.param<std::string>("ttc") == "signed" ? pps::TtcDefinition::kSigned
                                                    : pps::TtcDefinition::kUnsigned;
  p.parzen.sigma_scale = ctx.param<double>("sigma_scale");
  pps::parse_kernel_anchor(ctx.param<std::string>("kernel_anchor"), p.parzen.anchor);
  p.rf.shape = ctx.param<std::string>("rf_shape") == "cone" ? pps::RfShape::kCone
                                                            : pps::RfShape::kConeMirroredCylinder;
  p.rf.half_angle_rad = deg_to_rad(ctx.param<double>("rf_half_angle_deg"));
  p.rf.range_m = ctx.param<double>("rf_range");
  p.buffer.horizon_s = ctx.param<double>("buffer_horizon");
  p.buffer.reset_after_s = ctx.param<double>("buffer_reset");
  pps::parse_pps_model(ctx.param<std::string>("model"), p.model);
  p.contact.min_events = ctx.param<int>("contact_min_events");
  p.contact.agreement_m = ctx.param<double>("contact_agreement");
  return p;
}

}  // namespace somasim::plugins
