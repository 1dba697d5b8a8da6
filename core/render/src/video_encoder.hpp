#pragma once
// A video file written on its own thread: frames are handed over (copied) and encoded in order
// while the run goes on, so that a run's recording costs the simulation thread one copy per
// frame. The same frames give the same file, whatever the timing.
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <filesystem>
#include <mutex>
#include <thread>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

namespace somasim::render {

class VideoEncoder {
 public:
  /// `file` (MPEG-4 part 2 in MP4) at `fps` frames per second; opened at the first frame, whose
  /// size every later frame must have. At most `max_pending` frames wait for the encoder; a
  /// frame beyond that waits in add() (memory stays bounded however slow the encoder is).
  VideoEncoder(std::filesystem::path file, double fps, std::size_t max_pending = 8);
  /// Ends the encoder's thread after the frames handed over (errors are dropped: call close()).
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;
  VideoEncoder(VideoEncoder&&) = delete;
  VideoEncoder& operator=(VideoEncoder&&) = delete;

  /// Hands over a BGR 8-bit frame. Throws RunError (naming the file) when the video cannot be
  /// opened or a frame's size differs from the first's; the error of a frame handed over
  /// earlier may show here or in close().
  void add(const cv::Mat& bgr);
  /// Encodes every frame handed over and closes the file; throws the first error, if any.
  /// Idempotent.
  void close();

 private:
  void encode_loop();
  void encode(const cv::Mat& bgr);
  void rethrow_error_locked();

  std::filesystem::path file_;
  double fps_;
  std::size_t max_pending_;
  cv::VideoWriter writer_;  // the encoder thread's alone
  cv::Size size_;           // of the first frame handed over

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<cv::Mat> pending_;
  bool closing_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace somasim::render
