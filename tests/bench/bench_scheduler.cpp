// Scheduler overhead: Simulation::step() over a chain of trivial nodes, per node tick, against
// a same-run baseline that calls step() on the same kind of plugin objects directly.
//
// Graph: one counter feeding a chain of adders (a_i = a_{i-1}), every node at the base rate, so
// each base tick steps every node once. The plugins do almost nothing: what is left is the
// framework's per-node cost (rate check, bookkeeping, recorder lookup, delayed-edge copies).
#include <benchmark/benchmark.h>
#include <spdlog/sinks/null_sink.h>

#include <filesystem>

#include "node_runtime.hpp"  // internal: the baseline wires nodes by hand
#include "somasim/experiment.hpp"
#include "somasim/plugin_registry.hpp"
#include "somasim/simulation.hpp"

namespace {
namespace fs = std::filesystem;
using namespace somasim;

constexpr int kNodes = 20;

std::string chain_yaml(int nodes) {
  std::string y = "experiment: bench\nduration_s: 1.0e9\nnodes:\n";
  y += "  n0: {plugin: counter, params: {start: 0}}\n";
  for (int i = 1; i < nodes; ++i)
    y += "  n" + std::to_string(i) + ": {plugin: adder, inputs: {a: n" + std::to_string(i - 1) +
         ".sum}}\n";
  // n1 reads the counter's "value", not "sum".
  const std::string wrong = "a: n0.sum";
  y.replace(y.find(wrong), wrong.size(), "a: n0.value");
  return y;
}

struct Fixture {
  PluginRegistry registry{{SOMASIM_TEST_PLUGIN_DIR}};
  Experiment exp;
  std::shared_ptr<spdlog::logger> log =
      std::make_shared<spdlog::logger>("bench", std::make_shared<spdlog::sinks::null_sink_mt>());
  fs::path out = fs::temp_directory_path() / "somasim-bench-scheduler";
  Fixture() {
    exp = load_experiment_text(chain_yaml(kNodes), "bench.yaml", ".", registry);
    fs::create_directories(out);
  }
  ~Fixture() {
    std::error_code ec;
    fs::remove_all(out, ec);
  }
};

void BM_SimulationStep(benchmark::State& state) {
  Fixture f;
  Simulation sim(f.exp, f.out, f.log);
  sim.configure();
  sim.start();
  for (auto _ : state) benchmark::DoNotOptimize(sim.step());
  state.counters["per_node_tick"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kNodes,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_SimulationStep);

// Baseline: the same plugins, wired the same way, stepped by a plain loop of virtual calls.
void BM_DirectVirtualCalls(benchmark::State& state) {
  Fixture f;
  Simulation host(f.exp, f.out, f.log);  // only provides the seed/time to the contexts
  std::vector<std::unique_ptr<NodeRuntime>> nodes;
  for (const auto& ns : f.exp.nodes) {
    auto rt = std::make_unique<NodeRuntime>(host, ns, f.log);
    rt->plugin = ns.spec->factory();
    for (const auto& p : ns.spec->ports())
      if (p.direction == PortDirection::Output) rt->outputs[p.name] = p.type->create();
    for (const auto& w : ns.inputs)
      for (auto& producer : nodes)
        if (producer->spec.name == w.from_node)
          rt->inputs[w.port] = producer->outputs.at(w.from_port).get();
    rt->plugin->configure(rt->context);
    nodes.push_back(std::move(rt));
  }
  for (auto _ : state) {
    for (auto& n : nodes) n->plugin->step(n->context);
    benchmark::ClobberMemory();
  }
  state.counters["per_node_tick"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kNodes,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_DirectVirtualCalls);

}  // namespace
