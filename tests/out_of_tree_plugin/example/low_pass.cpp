// An example plugin written outside the somasim tree: a first-order low-pass filter.
//   y_k = y_{k-1} + a (g u_k - y_{k-1}),  a = dt / (tau + dt)
// (the exact discretisation of tau dy/dt + y = g u for a step held over dt; tau = 0 passes
// g u straight through).
#include <somasim/plugin.hpp>
#include <somasim/port_types.hpp>

namespace example {

class LowPass : public somasim::Plugin {
 public:
  static somasim::PluginSpec spec() {
    somasim::PluginSpec s("low_pass", "First-order low-pass filter of a scalar (example plugin).");
    s.add_double("time_constant_s")
        .unit_is("s")
        .defaults(0.1)
        .at_least(0)
        .describe("time constant tau");
    s.add_double("gain").defaults(1.0).describe("static gain g");
    s.input<double>("in", "the signal u");
    s.output<double>("out", "the filtered signal y");
    return s;
  }

  void configure(somasim::NodeContext& ctx) override {
    in_ = &ctx.input<double>("in");
    out_ = &ctx.output<double>("out");
    gain_ = ctx.param<double>("gain");
    const double tau = ctx.param<double>("time_constant_s");
    alpha_ = ctx.period_s() / (tau + ctx.period_s());
  }
  void step(somasim::NodeContext&) override { *out_ += alpha_ * (gain_ * *in_ - *out_); }
  void finish(somasim::NodeContext& ctx) override { ctx.report_metric("final_output", *out_); }

 private:
  const double* in_ = nullptr;
  double* out_ = nullptr;
  double gain_ = 1.0, alpha_ = 1.0;
};

}  // namespace example

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<example::LowPass>();
}
