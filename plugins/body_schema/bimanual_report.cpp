#include "bimanual_report.hpp"

#include "sample_stats.hpp"

#include <fmt/format.h>

#include <cmath>

#include "somasim/robot/experiment_robot.hpp"

namespace somasim::plugins {
namespace {

void put_mean_sd(NodeContext& ctx, const std::string& key, const std::vector<double>& v) {
  const MeanSd s = mean_sd(v);
  ctx.report_metric(key, v.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.mean));
  ctx.report_metric(key + "_sd", v.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.sd));
}

}  // namespace

PluginSpec BimanualReport::spec() {
  PluginSpec s("bimanual_report",
               "Positioning error of a bimanual reach (fingertips touching, palms a given "
               "distance apart) from the world's true link poses, at the end of the open and of "
               "the closed loop of every movement.");
  robot::add_robot_param(s);
  s.add_string_list("fingertips")
      .defaults(std::vector<std::string>{"r_index_tip", "l_index_tip"})
      .size(2)
      .describe("the two frames that should touch");
  s.add_string_list("palms")
      .defaults(std::vector<std::string>{"r_palm", "l_palm"})
      .size(2)
      .describe("the two palm frames");
  s.add_double("palm_distance")
      .defaults(0.12)
      .unit_is("m")
      .at_least(0.0)
      .describe("desired distance between the palm frames' origins");
  s.add_int("open_loop_frames")
      .defaults(std::int64_t{120})
      .at_least(1)
      .describe("as the reach controllers'");
  s.add_int("closed_loop_frames")
      .defaults(std::int64_t{50})
      .at_least(0)
      .describe("as the reach controllers'");
  s.input<LinkPoses>("true_link_poses", "the world's link poses");
  s.input<ReachPhase>("phase", "one of the (synchronous) reach controllers' phase");
  return s;
}

void BimanualReport::configure(NodeContext& ctx) {
  model_ = robot::experiment_robot(ctx);
  const auto tips = ctx.param<std::vector<std::string>>("fingertips");
  const auto palms = ctx.param<std::vector<std::string>>("palms");
  for (int k = 0; k < 2; ++k) {
    try {
      tips_[k] = model_->frame_ref(tips[static_cast<std::size_t>(k)]);
    } catch (const InputError& e) {
      ctx.param_error("fingertips", e.what());
    }
    try {
      palms_[k] = model_->frame_ref(palms[static_cast<std::size_t>(k)]);
    } catch (const InputError& e) {
      ctx.param_error("palms", e.what());
    }
  }
  palm_distance_ = ctx.param<double>("palm_distance");
  open_frames_ = ctx.param<int>("open_loop_frames");
  closed_frames_ = ctx.param<int>("closed_loop_frames");
  poses_ = &ctx.input<LinkPoses>("true_link_poses");
  phase_ = &ctx.input<ReachPhase>("phase");
}

void BimanualReport::step(NodeContext&) {
  const bool end_open = phase_->frame == open_frames_;
  const bool end_closed = closed_frames_ > 0 && phase_->frame == open_frames_ + closed_frames_;
  if ((!end_open && !end_closed) || poses_->poses.empty() ||
      (phase_->stage != ReachStage::kOpenLoop && phase_->stage != ReachStage::kClosedLoop))
    return;
  auto at = [&](const robot::FrameRef& f) -> Eigen::Vector3d {
    return (poses_->poses[static_cast<std::size_t>(f.link)] * f.pose).translation();
  };
  const double gap = (at(tips_[0]) - at(tips_[1])).norm() * 1e3;
  const double palm = std::abs((at(palms_[0]) - at(palms_[1])).norm() - palm_distance_) * 1e3;
  (end_open ? gap_open_ : gap_closed_).push_back(gap);
  (end_open ? palm_open_ : palm_closed_).push_back(palm);
}

void BimanualReport::finish(NodeContext& ctx) {
  put_mean_sd(ctx, "bimanual_tip_gap_open_loop_mm", gap_open_);
  put_mean_sd(ctx, "bimanual_tip_gap_closed_loop_mm", gap_closed_);
  put_mean_sd(ctx, "bimanual_palm_distance_error_open_loop_mm", palm_open_);
  put_mean_sd(ctx, "bimanual_palm_distance_error_closed_loop_mm", palm_closed_);
}

}  // namespace somasim::plugins
