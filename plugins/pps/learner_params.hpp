#pragma once
// The pps_learner's parameter schema and its conversion to somasim::pps::LearnerParams.
#include "somasim/plugin.hpp"
#include "somasim/pps/body_part_learner.hpp"

namespace somasim::plugins {

/// Declares the learning parameters (grid, Parzen variant, RF, TTC definition, buffer). Defaults
/// are the paper text's (Roncone et al. 2016, Learning peripersonal space representation through
/// artificial skin for avoidance and reaching with whole body surface); a parameter's description
/// gives the released code's value where it differs.
void declare_learner_params(PluginSpec& spec);

/// Reads them back (after validation by the loader); InputError for inconsistent values.
pps::LearnerParams read_learner_params(const NodeContext& ctx);

}  // namespace somasim::plugins
