#pragma once
// joint_command_mux: merges up to four JointCommand inputs (in0..in3, each optional) so that
// several controllers can drive one world. Conflicts (two inputs commanding the same dof) are
// resolved by `conflict`: last_wins (the higher-numbered input wins) or error (the run stops
// with a message naming both inputs and the dof). Inputs that have not produced a command yet
// (empty) are ignored; dofs nobody commands get mode kNone.
#include <array>

#include "somasim/config.hpp"
#include "somasim/control/joint_command_merge.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"

namespace somasim::plugins {

class JointCommandMux : public Plugin {
 public:
  static constexpr int kInputs = 4;
  struct Config {
    control::MergeConflict conflict = control::MergeConflict::kLastWins;
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    std::array<OptionalIn<JointCommand>, kInputs> in;  // in0..in3
    Out<JointCommand> command;
    template <class V>
    void visit(V& v);
  };
  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;

 private:
  Config config_;
  Ports ports_;
  std::vector<const JointCommand*> inputs_;  // null where unwired
  std::vector<std::string> names_;
};

}  // namespace somasim::plugins
