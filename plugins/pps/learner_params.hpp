#pragma once
// The pps_learner's parameter schema and its conversion to somasim::pps::LearnerParams.
#include "somasim/plugin.hpp"
#include "somasim/pps/body_part_learner.hpp"

namespace somasim::plugins {

/// Declares the learning parameters (grid, Parzen variant, RF, TTC definition, buffer).
/// Defaults are the paper text's; PAPERS.md A lists the released code's values.
void declare_learner_params(PluginSpec& spec);

/// Reads them back (after validation by the loader); InputError for inconsistent values.
pps::LearnerParams read_learner_params(const NodeContext& ctx);

}  // namespace somasim::plugins
