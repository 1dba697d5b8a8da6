// Small plugins used by the core's tests (scheduler, loader, runner). Not installed.
#include <fstream>
#include <map>
#include <memory>
#include <random>

#include "somasim/experiment.hpp"
#include "somasim/plugin.hpp"
#include "somasim/port_types.hpp"

namespace somasim::test {

/// A port value whose storage is shared by `operator=` (as a cv::Mat's is): only the deep copy
/// hook keeps a delayed edge's buffer apart from the producer's value. Counts its copies.
struct SharedBuffer {
  std::shared_ptr<std::vector<double>> values = std::make_shared<std::vector<double>>();
};
inline int g_buffer_copies = 0;

/// Records a SharedBuffer as `<stem>.txt`, one line "t: v1 v2 ..." per producer step.
class BufferRecorder final : public PortRecorder {
 public:
  BufferRecorder(const SharedBuffer* value, const RecordTarget& target)
      : value_(value), out_(target.dir / (target.stem + ".txt")) {}
  void write(double time_s) override {
    out_ << time_s << ":";
    for (double v : *value_->values) out_ << " " << v;
    out_ << "\n";
  }
  void flush() override { out_.flush(); }

 private:
  const SharedBuffer* value_;
  std::ofstream out_;
};

/// A type named like the framework's "scalar" but of another size (an ABI mismatch).
struct WideScalar {
  double value = 0, extra = 0;
};

}  // namespace somasim::test

namespace somasim {
template <>
struct PortTraits<test::SharedBuffer> {
  static constexpr const char* name = "test_shared_buffer";
  static void copy(test::SharedBuffer& dst, const test::SharedBuffer& src) {
    ++test::g_buffer_copies;
    dst.values = std::make_shared<std::vector<double>>(*src.values);
  }
  static std::unique_ptr<PortRecorder> recorder(const test::SharedBuffer* value,
                                                const RecordTarget& target) {
    return std::make_unique<test::BufferRecorder>(value, target);
  }
};
template <>
struct PortTraits<test::WideScalar> {
  static constexpr const char* name = "scalar";
};
}  // namespace somasim

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
    if (stop_after_ > 0) ctx.report_progress(steps_, stop_after_, "counts");
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

/// Writes its step count into a SharedBuffer, in place (the storage stays the same).
class BufferSource : public Plugin {
 public:
  static PluginSpec spec() {
    PluginSpec s("buffer_source", "Counts its steps into a shared buffer (test plugin).");
    s.output<SharedBuffer>("buffer", "{steps so far}");
    return s;
  }
  void configure(NodeContext& ctx) override { out_ = &ctx.output<SharedBuffer>("buffer"); }
  void step(NodeContext&) override { out_->values->assign(1, ++steps_); }

 private:
  SharedBuffer* out_ = nullptr;
  double steps_ = 0;
};

/// Reads a SharedBuffer; reports what it saw at each step and the copies made so far.
class BufferSink : public Plugin {
 public:
  static PluginSpec spec() {
    PluginSpec s("buffer_sink", "Reads a shared buffer (test plugin).");
    s.input<SharedBuffer>("in", "any buffer");
    return s;
  }
  void configure(NodeContext& ctx) override {
    in_ = &ctx.input<SharedBuffer>("in");
    g_buffer_copies = 0;
  }
  void step(NodeContext&) override {
    seen_.push_back(in_->values->empty() ? -1.0 : in_->values->front());
  }
  void finish(NodeContext& ctx) override {
    ctx.report_metric("seen", seen_);
    ctx.report_metric("copies", g_buffer_copies);
  }

 private:
  const SharedBuffer* in_ = nullptr;
  std::vector<double> seen_;
};

/// Outputs a WideScalar under the name "scalar" (for the size check of the wiring).
class WideSource : public Plugin {
 public:
  static PluginSpec spec() {
    PluginSpec s("wide_source", "Outputs a 'scalar' of the wrong size (test plugin).");
    s.output<WideScalar>("value", "not really a scalar");
    return s;
  }
  void configure(NodeContext&) override {}
  void step(NodeContext&) override {}
};

/// Reports its list parameter and the robot it names (for the loader's tests).
class ListAndRobot : public Plugin {
 public:
  static PluginSpec spec() {
    PluginSpec s("list_and_robot", "Reports a word list and a robot (test plugin).");
    s.add_string_list("words").defaults(std::vector<std::string>{"a", "b"}).describe("any words");
    s.add_string_list("colours")
        .defaults(std::vector<std::string>{})
        .one_of({"red", "green"})
        .describe("words from a fixed set");
    s.add_string("robot").defaults(std::string()).describe("a robot name ('' = the only one)");
    s.add_bool("use_robot").defaults(false).describe("look the robot up in configure()");
    return s;
  }
  void configure(NodeContext& ctx) override {
    words_ = ctx.param<std::vector<std::string>>("words");
    if (ctx.param<bool>("use_robot")) {
      robot_file_ = ctx.robot_spec("robot").file.filename().string();
      // One value per run and key, whichever node asks first.
      shared_ = ctx.run_shared<int>("test:shared", [] {
        ++g_makes;
        return std::make_shared<const int>(g_makes);
      });
    }
  }
  void step(NodeContext&) override {}
  void finish(NodeContext& ctx) override {
    ctx.report_metric("words", words_);
    ctx.report_metric("robot_file", robot_file_);
    ctx.report_metric("shared", shared_ ? *shared_ : 0);
  }
  static inline int g_makes = 0;

 private:
  std::vector<std::string> words_;
  std::string robot_file_;
  std::shared_ptr<const int> shared_;
};

}  // namespace somasim::test

namespace somasim::test {

// Reports which of its outputs something reads (NodeContext::is_read), as metrics.
class ReadProbe : public Plugin {
 public:
  static PluginSpec spec() {
    PluginSpec s("read_probe", "Reports which of its outputs are read (test plugin).");
    s.output<double>("a", "an output");
    s.output<double>("b", "another output");
    s.output<double>("c", "a third output");
    return s;
  }
  void configure(NodeContext& ctx) override {
    for (const char* port : {"a", "b", "c"}) read_[port] = ctx.is_read(port);
  }
  void step(NodeContext&) override {}
  void finish(NodeContext& ctx) override {
    for (const auto& [port, read] : read_) ctx.report_metric(std::string("read_") + port, read);
  }

 private:
  std::map<std::string, bool> read_;
};

}  // namespace somasim::test

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::test::BufferSource>();
  registrar.add<somasim::test::BufferSink>();
  registrar.add<somasim::test::WideSource>();
  registrar.add<somasim::test::ListAndRobot>();
  registrar.add<somasim::test::Counter>();
  registrar.add<somasim::test::Adder>();
  registrar.add<somasim::test::VectorSink>();
  registrar.add<somasim::test::ReadProbe>();
}
