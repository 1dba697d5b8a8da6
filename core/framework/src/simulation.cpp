#include "somasim/simulation.hpp"

#include <algorithm>
#include <cmath>

#include "node_runtime.hpp"
#include "somasim/interrupt.hpp"
#include "somasim/rng.hpp"

namespace somasim {
namespace fs = std::filesystem;

NodeRuntime::NodeRuntime(Simulation& s, const NodeSpec& ns, std::shared_ptr<spdlog::logger> l)
    : sim(s),
      spec(ns),
      context(*this),
      rng(node_stream_seed(s.experiment().seed, ns.name)),
      log(std::move(l)) {}

Simulation::Simulation(const Experiment& experiment, fs::path out_dir,
                       std::shared_ptr<spdlog::logger> logger)
    : exp_(experiment), out_dir_(std::move(out_dir)), logger_(std::move(logger)) {
  total_ticks_ = static_cast<std::int64_t>(std::floor(exp_.duration_s * exp_.base_rate_hz + 1e-9));
}

Simulation::~Simulation() {
  for (auto& r : recorders_) {
    try {
      r->flush();
    } catch (const std::exception&) {  // finish() reports write errors; nothing more to save
    }
  }
}

bool Simulation::output_read(const std::string& node, const std::string& port) const {
  if (all_outputs_read_) return true;
  for (const RecordSpec& r : exp_.records)
    if (r.node == node && r.port == port) return true;
  for (const NodeSpec& n : exp_.nodes)
    for (const auto& w : n.inputs)
      if (w.from_node == node && w.from_port == port) return true;
  return false;
}

double Simulation::time_s() const {
  return static_cast<double>(tick_) / exp_.base_rate_hz;
}

void Simulation::configure() {
  SOMASIM_CHECK(!configured_, "configure() called twice");
  configured_ = true;
  for (const auto& ns : exp_.nodes) {
    auto node_log =
        std::make_shared<spdlog::logger>(ns.name, logger_->sinks().begin(), logger_->sinks().end());
    node_log->set_level(logger_->level());
    auto rt = std::make_unique<NodeRuntime>(*this, ns, node_log);
    rt->plugin = ns.spec->factory();
    for (const auto& p : ns.spec->ports())
      if (p.direction == PortDirection::Output) rt->outputs[p.name] = p.type->create();
    nodes_.push_back(std::move(rt));
  }
  auto runtime_of = [&](const std::string& name) -> NodeRuntime& {
    for (auto& n : nodes_)
      if (n->spec.name == name) return *n;
    SOMASIM_CHECK(false, "wired node vanished after validation");
  };
  for (auto& n : nodes_) {
    for (const auto& w : n->spec.inputs) {
      const PortSpec* in = n->spec.spec->find_port(w.port, PortDirection::Input);
      void* storage = nullptr;
      if (w.from_node == "harness") {
        storage = harness_port(w.from_port, in->type->name);
        if (!storage) {
          harness_ports_.push_back({w.from_port, in->type, in->type->create()});
          storage = harness_ports_.back().storage.get();
        }
      } else {
        const NodeRuntime& producer_node = runtime_of(w.from_node);
        void* producer = producer_node.outputs.at(w.from_port).get();
        storage = producer;
        if (w.delayed) {
          delayed_.push_back({in->type, &producer_node, producer, in->type->create()});
          storage = delayed_.back().buffer.get();
        }
      }
      n->inputs[w.port] = storage;
    }
  }
  for (int i : exp_.order) {
    current_node_ = nodes_[i]->spec.name;
    nodes_[i]->plugin->configure(nodes_[i]->context);
    ordered_.push_back(nodes_[i].get());
  }
  current_node_.clear();
}

void Simulation::start() {
  for (const auto& r : exp_.records) {
    for (auto& n : nodes_) {
      if (n->spec.name != r.node) continue;
      const PortSpec* out = n->spec.spec->find_port(r.port, PortDirection::Output);
      const RecordTarget target{out_dir_, r.node + "." + r.port, r.as == RecordAs::kVideo,
                                exp_.base_rate_hz / static_cast<double>(n->spec.period_ticks)};
      auto rec = out->type->make_recorder(*out->type, n->outputs.at(r.port).get(), target);
      n->recorders.push_back(rec.get());  // indexed per node: no scan in step()
      recorders_.push_back(std::move(rec));
    }
  }
  for (int i : exp_.order) {
    current_node_ = nodes_[i]->spec.name;
    nodes_[i]->plugin->start(nodes_[i]->context);
  }
  current_node_.clear();
}

std::optional<Simulation::NodeProgress> Simulation::furthest_progress() const {
  std::optional<NodeProgress> best;
  double best_fraction = -1.0;
  for (const auto& n : nodes_) {
    if (n->progress_total <= 0) continue;
    const double f = static_cast<double>(n->progress_done) / static_cast<double>(n->progress_total);
    if (f > best_fraction) {
      best_fraction = f;
      best = NodeProgress{n->spec.name, n->progress_what, n->progress_done, n->progress_total};
    }
  }
  return best;
}

double Simulation::progress_fraction() const {
  double f =
      total_ticks_ > 0 ? static_cast<double>(tick_) / static_cast<double>(total_ticks_) : 0.0;
  if (const auto p = furthest_progress())
    f = std::max(f, static_cast<double>(p->done) / static_cast<double>(p->total));
  return std::clamp(f, 0.0, 1.0);
}

bool Simulation::step() {
  if (!stop_reason_.empty()) return false;
  if (tick_ >= total_ticks_) {
    stop_reason_ = "duration reached";
    return false;
  }
  if (interrupt_requested()) {
    stop_reason_ = "interrupted";
    return false;
  }
  // Hot loop (benchmarked in tests/bench/bench_scheduler.cpp): a compare instead of a
  // division per node, and the failing node's name is only copied when a step throws.
  const double t = time_s();
  for (NodeRuntime* n : ordered_) {
    if (n->next_tick != tick_) continue;
    n->next_tick += n->spec.period_ticks;
    n->last_step_tick = tick_;
    try {
      n->plugin->step(n->context);
    } catch (...) {
      current_node_ = n->spec.name;
      throw;
    }
    for (PortRecorder* r : n->recorders) r->write(t);
  }
  copy_delayed();
  ++tick_;
  return true;
}

void Simulation::copy_delayed() {
  for (auto& d : delayed_)
    if (d.producer_node->last_step_tick == tick_) d.type->copy(d.buffer.get(), d.producer);
}

std::string Simulation::finish() {
  std::string first_error;
  for (int i : exp_.order) {
    NodeRuntime& n = *nodes_[i];
    try {
      n.plugin->finish(n.context);
    } catch (const std::exception& e) {
      if (first_error.empty()) first_error = "node '" + n.spec.name + "' finish: " + e.what();
      logger_->error("node '{}' failed in finish(): {}", n.spec.name, e.what());
    }
    nlohmann::ordered_json m = nlohmann::ordered_json::object();
    for (const auto& [k, v] : n.metrics) m[k] = v;
    if (!m.empty()) metrics_[n.spec.name] = m;
  }
  for (auto& r : recorders_) {
    try {
      r->flush();
    } catch (const std::exception& e) {
      if (first_error.empty()) first_error = e.what();
      logger_->error("{}", e.what());
    }
  }
  return first_error;
}

void* Simulation::harness_port(const std::string& name, const std::string& type_name) {
  for (auto& h : harness_ports_)
    if (h.name == name) {
      if (h.type->name != type_name)
        throw InputError("harness input '" + name + "' is '" + h.type->name + "', not '" +
                         type_name + "'");
      return h.storage.get();
    }
  return nullptr;
}

void* Simulation::output_port(const std::string& node, const std::string& port,
                              const std::string& type_name) {
  for (auto& n : nodes_) {
    if (n->spec.name != node) continue;
    auto it = n->outputs.find(port);
    if (it == n->outputs.end())
      throw InputError("node '" + node + "' has no output '" + port + "'");
    const PortSpec* ps = n->spec.spec->find_port(port, PortDirection::Output);
    if (ps->type->name != type_name)
      throw InputError("output '" + node + "." + port + "' is '" + ps->type->name + "', not '" +
                       type_name + "'");
    return it->second.get();
  }
  throw InputError("no node '" + node + "'");
}

// --- NodeContext ---------------------------------------------------------------------------

const std::string& NodeContext::node_name() const {
  return rt_.spec.name;
}
const Params& NodeContext::params() const {
  return rt_.spec.params;
}
bool NodeContext::is_wired(const std::string& port) const {
  return rt_.inputs.count(port) != 0;
}
bool NodeContext::is_read(const std::string& port) const {
  return rt_.sim.output_read(rt_.spec.name, port);
}
double NodeContext::time_s() const {
  return rt_.sim.time_s();
}
std::int64_t NodeContext::tick() const {
  return rt_.sim.tick();
}
double NodeContext::rate_hz() const {
  return rt_.spec.rate_hz;
}
double NodeContext::duration_s() const {
  return rt_.sim.experiment().duration_s;
}
std::uint64_t NodeContext::seed() const {
  return rt_.sim.experiment().seed;
}
std::mt19937_64& NodeContext::rng() {
  return rt_.rng;
}
spdlog::logger& NodeContext::log() {
  return *rt_.log;
}

void NodeContext::request_stop(const std::string& reason) {
  if (rt_.sim.stop_reason_.empty())
    rt_.sim.stop_reason_ = "node '" + rt_.spec.name + "': " + reason;
}

void NodeContext::report_progress(std::int64_t done, std::int64_t total, const std::string& what) {
  rt_.progress_done = done;
  rt_.progress_total = total;
  if (rt_.progress_what != what) rt_.progress_what = what;
}

void NodeContext::report_metric(const std::string& name, nlohmann::json value) {
  for (auto& [k, v] : rt_.metrics)
    if (k == name) {
      v = std::move(value);
      return;
    }
  rt_.metrics.emplace_back(name, std::move(value));
}

namespace {
// "" if `name` is a relative path that stays below its folder, else why not.
std::string containment_problem(const std::string& name) {
  const fs::path p = name;
  if (name.empty()) return "is empty";
  if (p.is_absolute()) return "is an absolute path";
  for (const auto& part : p)
    if (part == "..") return "climbs out with '..'";
  if (p.filename().empty() || p.filename() == ".") return "names a folder, not a file";
  return "";
}
}  // namespace

namespace {
// `dir / file_name` with its folders created; RunError naming the node if it would leave `dir`.
fs::path contained_path(const fs::path& dir, const std::string& file_name, const std::string& node,
                        const std::string& what) {
  if (const std::string why = containment_problem(file_name); !why.empty())
    throw RunError("node '" + node + "': " + what + " '" + file_name + "' " + why +
                   "; it must stay inside " + dir.string());
  const fs::path file = dir / fs::path(file_name).lexically_normal();
  fs::create_directories(file.parent_path());
  return file;
}
}  // namespace

fs::path NodeContext::figure_path(const std::string& file_name) {
  return contained_path(rt_.sim.out_dir_ / "figures", file_name, rt_.spec.name, "figure file");
}

fs::path NodeContext::output_path(const std::string& file_name) {
  return contained_path(rt_.sim.out_dir_, file_name, rt_.spec.name, "output file");
}

fs::path NodeContext::output_path_param(const std::string& param) {
  return claim_output_file(param, params().get<std::string>(param));
}

namespace {
// Why `relative` (normalised, relative to the run folder) is one of the run's own files, or "".
std::string run_file_problem(const std::string& relative, const Experiment& exp) {
  static const char* const kRunFiles[] = {"metrics.json", "metrics.json.tmp", "log.txt",
                                          "experiment.resolved.yaml", "manifest.json"};
  for (const char* f : kRunFiles)
    if (relative == f) return "is one of the run folder's own files";
  for (const char* folder : {"figures", "frames"})  // figures; cameras' saved frames
    if (relative == folder || relative.rfind(std::string(folder) + "/", 0) == 0)
      return std::string("is the run's ") + folder + "/ folder or inside it";
  for (const RecordSpec& r : exp.records) {
    const std::string stem = r.node + "." + r.port;  // a CSV, or a folder of images
    if (relative == stem + ".csv" || relative == stem + ".mp4" || relative == stem ||
        relative.rfind(stem + "/", 0) == 0)
      return "is written by the recorder of '" + stem + "'";
  }
  return "";
}
}  // namespace

fs::path NodeContext::claim_output_file(const std::string& param, const std::string& name) {
  if (const std::string why = containment_problem(name); !why.empty())
    param_error(param, "output file '" + name + "' " + why +
                           "; expected a file name relative to the run folder");
  const std::string relative = fs::path(name).lexically_normal().generic_string();
  if (const std::string why = run_file_problem(relative, rt_.sim.experiment()); !why.empty())
    param_error(param, "output file '" + name + "' " + why + "; choose another name");
  const std::string owner = "node '" + rt_.spec.name + "', key 'params." + param + "'";
  const auto [it, inserted] = rt_.sim.claimed_outputs_.emplace(relative, owner);
  if (!inserted && it->second != owner)
    param_error(param, "output file '" + name + "' is written by " + it->second +
                           " already; choose another name");
  return output_path(name);
}

fs::path NodeContext::resolve_input_path(const std::string& path) const {
  const fs::path p = path;
  return p.is_absolute() ? p : (rt_.sim.experiment().base_dir / p).lexically_normal();
}

void NodeContext::param_error(const std::string& param, const std::string& message) const {
  auto it = rt_.spec.param_locations.find(param);
  const SourceLocation where = it != rt_.spec.param_locations.end() ? it->second : rt_.spec.where;
  throw InputError(where.str() + ": node '" + rt_.spec.name + "', key 'params." + param +
                   "': " + message);
}

void NodeContext::node_error(const std::string& message) const {
  throw InputError(rt_.spec.where.str() + ": node '" + rt_.spec.name + "': " + message);
}

const RobotSpec& NodeContext::robot_spec(const std::string& param) const {
  const std::string name = params().get<std::string>(param);
  const auto& robots = rt_.sim.experiment().robots;
  std::string declared;
  for (const RobotSpec& r : robots) declared += (declared.empty() ? "'" : ", '") + r.name + "'";
  if (name.empty()) {
    if (robots.size() == 1) return robots.front();
    param_error(param, robots.empty()
                           ? "no robot: declare one in the experiment's 'robots:' section "
                             "(NAME: description file)"
                           : "the experiment declares several robots (" + declared + "): name one");
  }
  if (const RobotSpec* r = rt_.sim.experiment().find_robot(name)) return *r;
  param_error(param, "no robot '" + name + "' in the experiment's 'robots:' section" +
                         (robots.empty() ? std::string(" (it declares none)")
                                         : " (declared: " + declared + ")"));
}

std::shared_ptr<const void> NodeContext::run_shared_erased(
    const std::string& key, const std::function<std::shared_ptr<const void>()>& make) {
  auto& slot = rt_.sim.run_shared_[key];
  if (!slot) slot = make();
  return slot;
}

void* NodeContext::port_storage(const std::string& port, PortDirection direction,
                                const PortTypeInfo& type) const {
  const PortSpec* ps = rt_.spec.spec->find_port(port, direction);
  SOMASIM_CHECK(ps != nullptr, "plugin used a port it did not declare in its spec");
  SOMASIM_CHECK(ps->type->name == type.name, "plugin used a port with another type than declared");
  if (direction == PortDirection::Output) return rt_.outputs.at(port).get();
  auto it = rt_.inputs.find(port);
  if (it == rt_.inputs.end())
    throw InputError("node '" + rt_.spec.name + "': optional input '" + port + "' is not wired");
  return it->second;
}

}  // namespace somasim
