#include "yarp_image_replay.hpp"

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace somasim::plugins {

template <class V>
void YarpImageReplay::Config::visit(V& v) {
  v.block(log);
  v.field("camera", camera)
      .doc(
          "the camera the images came from, written into each image (e.g. left_eye); a label "
          "for consumers, not checked against a robot");
}

template <class V>
void YarpImageReplay::Ports::visit(V& v) {
  v.port("image", image, "the latest recorded image due (rgb8)");
}

PluginSpec YarpImageReplay::spec() {
  return make_plugin_spec<Config, Ports>(
      "yarp_image_replay",
      "Replays images recorded by yarpdatadumper (one image file per data.log line) on an RGB "
      "image port at their recorded times.");
}

void YarpImageReplay::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  log_ = read_replay_log(ctx, config_, config_.log, recordings::DumpContent::kImage);
  cursor_ = std::make_unique<recordings::ReplayCursor>(log_.entries, config_.log.offset_s);
  log_timeline(ctx, log_);
}

void YarpImageReplay::step(NodeContext& ctx) {
  const auto due = cursor_->advance_to(ctx.time_s());
  if (due.empty()) return;
  skipped_ += static_cast<std::int64_t>(due.size()) - 1;
  const recordings::DumpEntry& e = due.back();
  const std::filesystem::path file = log_.image_file(e);
  const cv::Mat bgr = cv::imread(file.string(), cv::IMREAD_COLOR);
  if (bgr.empty())
    throw RunError(fmt::format("{}:{}: image file '{}' cannot be decoded as an image",
                               (log_.folder / "data.log").string(), e.line, file.string()));
  if (width_ == 0) {
    width_ = bgr.cols;
    height_ = bgr.rows;
  } else if (bgr.cols != width_ || bgr.rows != height_) {
    throw RunError(fmt::format("{}:{}: image '{}' is {}x{} px; the log's first image is {}x{}",
                               (log_.folder / "data.log").string(), e.line, file.string(), bgr.cols,
                               bgr.rows, width_, height_));
  }
  RgbImage& out = *ports_.image;
  cv::cvtColor(bgr, out.data, cv::COLOR_BGR2RGB);
  out.encoding = ImageEncoding::kRgb8;
  out.camera = config_.camera;
  out.time_s = cursor_->due_time(e);
  ++out.frame;
}

void YarpImageReplay::finish(NodeContext& ctx) {
  if (!cursor_) return;
  report_replay(ctx, log_, *cursor_);
  ctx.report_metric("skipped", skipped_);
}

}  // namespace somasim::plugins
