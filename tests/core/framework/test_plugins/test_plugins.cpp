// Small plugins used by the core's tests (scheduler, loader, runner). Not installed.
#include <random>

#include "somasim/plugin.hpp"
#include "somasim/port_types.hpp"

namespace somasim::test {

/// Outputs start + increment × (number of steps so far).
class Counter : public Plugin {
 public:
  static PluginSpec spec() {
    PluginSpec s("counter", "Counts its own steps (test plugin).");
    s.add_double("start").unit_is("").describe("first value (required)");
    s.add_double("increment").defaults(1.0).range(-100, 100).describe("added at each step");
    s.add_string("mode")
        .defaults(std::string("plain"))
        .one_of({"plain", "noisy"})
        .describe("noisy adds N(0,1)");
    s.add_int("stop_after")
        .defaults(std::int64_t{0})
        .at_least(0)
        .describe("request a stop after N steps (0: never)");
    s.add_list("offset")
        .defaults(std::vector<double>{0, 0, 0})
        .size(3)
        .unit_is("m")
        .describe("a vector");
    s.add_bool("fail").defaults(false).describe("throw a RunError at the 3rd step");
    s.output<double>("value", "the count");
    s.output<Eigen::Vector3d>("vector", "offset scaled by the count");
    return s;
  }
  void configure(NodeContext& ctx) override {
    value_ = &ctx.output<double>("value");
    vector_ = &ctx.output<Eigen::Vector3d>("vector");
    *value_ = ctx.param<double>("start");
    increment_ = ctx.param<double>("increment");
    noisy_ = ctx.param<std::string>("mode") == "noisy";
    stop_after_ = ctx.param<int>("stop_after");
    fail_ = ctx.param<bool>("fail");
    const auto off = ctx.param<std::vector<double>>("offset");
    offset_ = Eigen::Vector3d(off[0], off[1], off[2]);
  }
  void step(NodeContext& ctx) override {
    ++steps_;
    if (fail_ && steps_ == 3) throw RunError("deliberate failure");
    *value_ += increment_;
    if (noisy_) *value_ += std::normal_distribution<double>(0, 1)(ctx.rng());
    *vector_ = offset_ * static_cast<double>(steps_);
    if (stop_after_ > 0 && steps_ >= stop_after_) ctx.request_stop("counted enough");
  }
  void finish(NodeContext& ctx) override {
    ctx.report_metric("steps", steps_);
    ctx.report_metric("final", *value_);
  }

 private:
  double* value_ = nullptr;
  Eigen::Vector3d* vector_ = nullptr;
  Eigen::Vector3d offset_;
  double increment_ = 1;
  int steps_ = 0, stop_after_ = 0;
  bool noisy_ = false, fail_ = false;
};

/// Outputs a + b (b optional); records the history of a for order tests.
class Adder : public Plugin {
 public:
  static PluginSpec spec() {
    PluginSpec s("adder", "Adds its inputs (test plugin).");
    s.input<double>("a", "first term");
    s.input<double>("b", "second term", /*optional=*/true);
    s.output<double>("sum", "a + b");
    return s;
  }
  void configure(NodeContext& ctx) override {
    a_ = &ctx.input<double>("a");
    b_ = ctx.is_wired("b") ? &ctx.input<double>("b") : nullptr;
    sum_ = &ctx.output<double>("sum");
  }
  void step(NodeContext&) override { *sum_ = *a_ + (b_ ? *b_ : 0.0); }
  void finish(NodeContext& ctx) override { ctx.report_metric("final", *sum_); }

 private:
  const double* a_ = nullptr;
  const double* b_ = nullptr;
  double* sum_ = nullptr;
};

/// Consumes a vector (for type-mismatch tests).
class VectorSink : public Plugin {
 public:
  static PluginSpec spec() {
    PluginSpec s("vector_sink", "Takes a vector3 (test plugin).");
    s.input<Eigen::Vector3d>("in", "any vector");
    return s;
  }
  void configure(NodeContext&) override {}
  void step(NodeContext&) override {}
};

}  // namespace somasim::test

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::test::Counter>();
  registrar.add<somasim::test::Adder>();
  registrar.add<somasim::test::VectorSink>();
}
