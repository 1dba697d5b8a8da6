#include "video_encoder.hpp"

#include <utility>

#include <fmt/format.h>

#include "somasim/error.hpp"

namespace somasim::render {

VideoEncoder::VideoEncoder(std::filesystem::path file, double fps, std::size_t max_pending)
    : file_(std::move(file)), fps_(fps), max_pending_(max_pending > 0 ? max_pending : 1) {}

VideoEncoder::~VideoEncoder() {
  try {
    close();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor cannot report; close() does
  }
}

void VideoEncoder::rethrow_error_locked() {
  if (error_) std::rethrow_exception(error_);
}

void VideoEncoder::add(const cv::Mat& bgr) {
  if (size_.empty()) size_ = bgr.size();
  if (bgr.size() != size_)
    throw RunError(fmt::format("video '{}': a frame is {} x {} px, the video {} x {}",
                               file_.string(), bgr.cols, bgr.rows, size_.width, size_.height));
  std::unique_lock lock(mutex_);
  rethrow_error_locked();
  if (closing_) throw RunError(fmt::format("video '{}': already closed", file_.string()));
  changed_.wait(lock, [&] { return pending_.size() < max_pending_ || error_ != nullptr; });
  rethrow_error_locked();
  pending_.push_back(bgr.clone());
  if (!thread_.joinable()) thread_ = std::thread([this] { encode_loop(); });
  changed_.notify_all();
}

void VideoEncoder::close() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
  if (writer_.isOpened()) writer_.release();
  std::lock_guard lock(mutex_);
  rethrow_error_locked();
}

void VideoEncoder::encode_loop() {
  for (;;) {
    cv::Mat frame;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return !pending_.empty() || closing_; });
      if (pending_.empty()) return;  // closing, everything encoded
      frame = std::move(pending_.front());
    }
    try {
      encode(frame);
    } catch (...) {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
      pending_.clear();
      changed_.notify_all();
      return;
    }
    std::lock_guard lock(mutex_);
    pending_.pop_front();
    changed_.notify_all();
  }
}

void VideoEncoder::encode(const cv::Mat& bgr) {
  if (!writer_.isOpened()) {
    writer_.open(file_.string(), cv::VideoWriter::fourcc('m', 'p', '4', 'v'), fps_, bgr.size(),
                 true);
    if (!writer_.isOpened())
      throw RunError(
          fmt::format("video '{}': cannot be written (no MP4 encoder in OpenCV?)", file_.string()));
  }
  writer_.write(bgr);
}

}  // namespace somasim::render
