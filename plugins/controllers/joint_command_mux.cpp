#include "joint_command_mux.hpp"

namespace somasim::plugins {

namespace {
// The name of input port i: in0 .. in3.
std::string input_port(int i) {
  return "in" + std::to_string(i);
}
}  // namespace

template <class V>
void JointCommandMux::Config::visit(V& v) {
  v.field("conflict", conflict)
      .doc(
          "two inputs commanding the same joint: last_wins (the higher-numbered input wins) or "
          "error (the run stops)");
}

template <class V>
void JointCommandMux::Ports::visit(V& v) {
  for (int i = 0; i < kInputs; ++i)
    v.port(input_port(i), in[static_cast<std::size_t>(i)],
           "joint commands of a controller (optional; later inputs win)");
  v.port("command", command, "the merged commands");
}

PluginSpec JointCommandMux::spec() {
  return make_plugin_spec<Config, Ports>(
      "joint_command_mux", "Merges up to four controllers' joint commands (in0..in3) into one.");
}

void JointCommandMux::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  for (int i = 0; i < kInputs; ++i) {
    inputs_.push_back(ports_.in[static_cast<std::size_t>(i)].get());
    names_.push_back(input_port(i));
  }
}

void JointCommandMux::step(NodeContext& ctx) {
  const std::string problem =
      control::merge_joint_commands(inputs_, config_.conflict, *ports_.command, names_);
  if (!problem.empty()) throw RunError(ctx.node_name() + ": " + problem);
}

}  // namespace somasim::plugins
