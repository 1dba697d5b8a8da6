#include "joint_command_mux.hpp"

namespace somasim::plugins {

PluginSpec JointCommandMux::spec() {
  PluginSpec s("joint_command_mux",
               "Merges up to four controllers' joint commands (in0..in3) into one.");
  s.add_string("conflict")
      .defaults(std::string("last_wins"))
      .one_of({"last_wins", "error"})
      .describe(
          "two inputs commanding the same joint: last_wins (the higher-numbered input wins) or "
          "error (the run stops)");
  for (int i = 0; i < kInputs; ++i)
    s.input<JointCommand>("in" + std::to_string(i),
                          "joint commands of a controller (optional; later inputs win)",
                          /*optional=*/true);
  s.output<JointCommand>("command", "the merged commands");
  return s;
}

void JointCommandMux::configure(NodeContext& ctx) {
  conflict_ = ctx.param<std::string>("conflict") == "error" ? control::MergeConflict::kError
                                                            : control::MergeConflict::kLastWins;
  for (int i = 0; i < kInputs; ++i) {
    const std::string port = "in" + std::to_string(i);
    inputs_.push_back(ctx.is_wired(port) ? &ctx.input<JointCommand>(port) : nullptr);
    names_.push_back(port);
  }
  output_ = &ctx.output<JointCommand>("command");
}

void JointCommandMux::step(NodeContext& ctx) {
  const std::string problem = control::merge_joint_commands(inputs_, conflict_, *output_, names_);
  if (!problem.empty()) throw RunError(ctx.node_name() + ": " + problem);
}

}  // namespace somasim::plugins
