// An example plugin written outside the somasim tree: a first-order low-pass filter.
//   y_k = y_{k-1} + a (g u_k - y_{k-1}),  a = dt / (tau + dt)
// (the exact discretisation of tau dy/dt + y = g u for a step held over dt; tau = 0 passes
// g u straight through).
#include <somasim/config.hpp>
#include <somasim/plugin.hpp>
#include <somasim/plugin_ports.hpp>
#include <somasim/port_types.hpp>

namespace example {

class LowPass : public somasim::Plugin {
 public:
  // Parameters: each member has its default; visit() names it once, with unit, range and doc.
  struct Config {
    double time_constant_s = 0.1;  // [s]
    double gain = 1.0;
    template <class V>
    void visit(V& v) {
      v.field("time_constant_s", time_constant_s).unit("s").at_least(0).doc("time constant tau");
      v.field("gain", gain).doc("static gain g");
    }
  };
  // Ports, named once in the same way.
  struct Ports {
    somasim::In<double> in;
    somasim::Out<double> out;
    template <class V>
    void visit(V& v) {
      v.port("in", in, "the signal u");
      v.port("out", out, "the filtered signal y");
    }
  };

  static somasim::PluginSpec spec() {
    return somasim::make_plugin_spec<Config, Ports>(
        "low_pass", "First-order low-pass filter of a scalar (example plugin).");
  }

  void configure(somasim::NodeContext& ctx) override {
    const auto config = somasim::read_config<Config>(ctx);
    somasim::bind_ports(ctx, ports_);
    gain_ = config.gain;
    alpha_ = ctx.period_s() / (config.time_constant_s + ctx.period_s());
  }
  void step(somasim::NodeContext&) override {
    *ports_.out += alpha_ * (gain_ * *ports_.in - *ports_.out);
  }
  void finish(somasim::NodeContext& ctx) override {
    if (ports_.out.bound()) ctx.report_metric("final_output", *ports_.out);
  }

 private:
  Ports ports_;
  double gain_ = 1.0, alpha_ = 1.0;
};

}  // namespace example

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<example::LowPass>();
}
