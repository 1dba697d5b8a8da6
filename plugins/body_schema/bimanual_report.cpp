#include "bimanual_report.hpp"

#include "sample_stats.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "somasim/robot/clearance.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/shape_distance.hpp"

namespace somasim::plugins {
namespace {

void put_mean_sd(NodeContext& ctx, const std::string& key, const std::vector<double>& v) {
  const MeanSd s = mean_sd(v);
  ctx.report_metric(key, v.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.mean));
  ctx.report_metric(key + "_sd", v.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.sd));
}

}  // namespace

template <class V>
void BimanualReport::Config::visit(V& v) {
  v.block(robot);
  v.field("fingertips", fingertips).size(2).doc("the two frames that should touch");
  v.field("palms", palms).size(2).doc("the two palm frames");
  v.field("palm_distance", palm_distance)
      .unit("m")
      .at_least(0.0)
      .doc("desired distance between the palm frames' origins");
  v.field("open_loop_frames", open_loop_frames).at_least(1).doc("as the reach controllers'");
  v.field("closed_loop_frames", closed_loop_frames).at_least(0).doc("as the reach controllers'");
}

template <class V>
void BimanualReport::Ports::visit(V& v) {
  v.port("true_link_poses", true_link_poses, "the world's link poses");
  v.port("phase", phase, "one of the (synchronous) reach controllers' phase");
}

PluginSpec BimanualReport::spec() {
  return make_plugin_spec<Config, Ports>(
      "bimanual_report",
      "Positioning error of a bimanual reach (fingertips touching, palms a given "
      "distance apart) from the world's true link poses, at the end of the open and of "
      "the closed loop of every movement.");
}

void BimanualReport::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  const auto tips = config_.fingertips;
  const auto palms = config_.palms;
  for (int k = 0; k < 2; ++k) {
    try {
      tips_[k] = model_->frame_ref(tips[static_cast<std::size_t>(k)]);
    } catch (const InputError& e) {
      config_error(ctx, config_, config_.fingertips, e.what());
    }
    try {
      palms_[k] = model_->frame_ref(palms[static_cast<std::size_t>(k)]);
    } catch (const InputError& e) {
      config_error(ctx, config_, config_.palms, e.what());
    }
  }
  // The finger of each tip: the collision shape of its link whose surface is nearest the frame.
  for (int k = 0; k < 2; ++k) {
    const robot::Link& link = model_->link(tips_[k].link);
    double nearest = std::numeric_limits<double>::infinity();
    for (const robot::Geometry& shape : link.collision) {
      const double d = std::abs(robot::distance_to_shape(shape, tips_[k].pose.translation()));
      if (d < nearest) nearest = d, fingers_[k] = &shape;
    }
    if (!fingers_[k] || fingers_[k]->type == robot::GeometryType::Mesh)
      config_error(ctx, config_, config_.fingertips,
                   fmt::format("frame '{}': its link '{}' has no primitive collision shape to "
                               "measure the fingers' surface gap on",
                               config_.fingertips[static_cast<std::size_t>(k)], link.name));
  }
  open_frames_ = config_.open_loop_frames;
  closed_frames_ = config_.closed_loop_frames;
  poses_ = &ports_.true_link_poses.get();
  phase_ = &ports_.phase.get();
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
  const double surface_gap =
      robot::shape_distance(*fingers_[0], poses_->poses[static_cast<std::size_t>(tips_[0].link)],
                            *fingers_[1], poses_->poses[static_cast<std::size_t>(tips_[1].link)]) *
      1e3;
  const double palm =
      std::abs((at(palms_[0]) - at(palms_[1])).norm() - config_.palm_distance) * 1e3;
  (end_open ? gap_open_ : gap_closed_).push_back(gap);
  (end_open ? surface_gap_open_ : surface_gap_closed_).push_back(surface_gap);
  (end_open ? palm_open_ : palm_closed_).push_back(palm);
}

void BimanualReport::finish(NodeContext& ctx) {
  put_mean_sd(ctx, "bimanual_tip_gap_open_loop_mm", gap_open_);
  put_mean_sd(ctx, "bimanual_tip_gap_closed_loop_mm", gap_closed_);
  put_mean_sd(ctx, "bimanual_tip_surface_gap_open_loop_mm", surface_gap_open_);
  put_mean_sd(ctx, "bimanual_tip_surface_gap_closed_loop_mm", surface_gap_closed_);
  put_mean_sd(ctx, "bimanual_palm_distance_error_open_loop_mm", palm_open_);
  put_mean_sd(ctx, "bimanual_palm_distance_error_closed_loop_mm", palm_closed_);
}

}  // namespace somasim::plugins
