#pragma once
// Internal: wiring checks and scheduling order of a parsed experiment.
#include "somasim/diagnostics.hpp"
#include "somasim/experiment.hpp"

namespace somasim::detail {

/// Checks inputs (node and port exist, types match, required inputs wired), records, and
/// cycles without a delayed edge; fills `exp.order` with a topological order of the nodes
/// (ties broken by file order, so the order is deterministic).
void check_graph(Experiment& exp, Diagnostics& diags, bool allow_harness_inputs);

}  // namespace somasim::detail
