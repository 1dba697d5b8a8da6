// The Image port: PNG encoding, the recorder that writes one PNG per new frame, and the one
// that writes a video (`record: [{port: NODE.PORT, as: video}]`).
#include "somasim/render/ports.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <system_error>
#include <vector>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "somasim/error.hpp"
#include "video_encoder.hpp"

namespace somasim {

const char* image_encoding_name(ImageEncoding encoding) {
  switch (encoding) {
    case ImageEncoding::kRgb8:
      return "rgb8";
    case ImageEncoding::kDepth32f:
      return "depth32f";
    case ImageEncoding::kId32s:
      return "id32s";
    case ImageEncoding::kNone:
      break;
  }
  return "none";
}

namespace render {
namespace {

cv::Mat png_pixels(const Image& image) {
  cv::Mat out;
  switch (image.encoding) {
    case ImageEncoding::kRgb8:
      cv::cvtColor(image.data, out, cv::COLOR_RGB2BGR);
      break;
    case ImageEncoding::kDepth32f:
      out.create(image.data.size(), CV_16U);
      for (int r = 0; r < image.data.rows; ++r)
        for (int c = 0; c < image.data.cols; ++c) {
          const double mm = std::round(1000.0 * image.data.at<float>(r, c));
          out.at<std::uint16_t>(r, c) =
              static_cast<std::uint16_t>(std::isfinite(mm) ? std::clamp(mm, 0.0, 65535.0) : 0.0);
        }
      break;
    case ImageEncoding::kId32s:
      out.create(image.data.size(), CV_16U);
      for (int r = 0; r < image.data.rows; ++r)
        for (int c = 0; c < image.data.cols; ++c)
          out.at<std::uint16_t>(r, c) =
              static_cast<std::uint16_t>(std::clamp(image.data.at<std::int32_t>(r, c), 0, 65535));
      break;
    case ImageEncoding::kNone:
      break;
  }
  return out;
}

class ImageRecorder : public PortRecorder {
 public:
  ImageRecorder(const Image* image, const RecordTarget& target)
      : image_(image), dir_(target.dir / target.stem) {
    std::error_code ec;
    std::filesystem::create_directories(dir_, ec);
    index_.open(dir_ / "index.csv");
    if (ec || !index_) throw RunError(fmt::format("cannot write into '{}'", dir_.string()));
    index_ << "time [s],frame,file\n";
  }
  void write(double time_s) override {
    if (image_->frame == 0 || image_->frame == last_frame_ || image_->data.empty()) return;
    last_frame_ = image_->frame;
    const std::string name = fmt::format("{:06d}.png", image_->frame);
    write_png(*image_, dir_ / name);
    index_ << fmt::format("{},{},{}\n", time_s, image_->frame, name);
  }
  void flush() override { index_.flush(); }

 private:
  const Image* image_;
  std::filesystem::path dir_;
  std::ofstream index_;
  std::uint64_t last_frame_ = 0;
};

// One video file per port: every new frame, at the camera's rate (MPEG-4 part 2 in MP4 through
// OpenCV's FFmpeg back end, encoded on its own thread; the same frames give the same bytes). RGB
// as it is; depth as grey (0 at the camera to white at 2 m and beyond); masks as grey ids
// (id x 37 mod 256).
class VideoRecorder : public PortRecorder {
 public:
  VideoRecorder(const Image* image, const RecordTarget& target)
      : image_(image),
        encoder_(target.dir / (target.stem + ".mp4"), target.rate_hz > 0 ? target.rate_hz : 30.0),
        file_(target.dir / (target.stem + ".mp4")) {}
  void write(double) override {
    if (image_->frame == 0 || image_->frame == last_frame_ || image_->data.empty()) return;
    last_frame_ = image_->frame;
    const cv::Mat frame = video_pixels(*image_);
    if (size_.empty()) size_ = frame.size();
    if (frame.size() != size_)
      throw RunError(fmt::format("video '{}': frame {} is {} x {} px, the video {} x {}",
                                 file_.string(), image_->frame, frame.cols, frame.rows, size_.width,
                                 size_.height));
    encoder_.add(frame);
  }
  void flush() override { encoder_.close(); }

 private:
  static cv::Mat video_pixels(const Image& image) {
    cv::Mat out = cv::Mat::zeros(image.data.size(), CV_8UC3);
    switch (image.encoding) {
      case ImageEncoding::kRgb8:
        cv::cvtColor(image.data, out, cv::COLOR_RGB2BGR);
        break;
      case ImageEncoding::kDepth32f:
        for (int r = 0; r < out.rows; ++r)
          for (int c = 0; c < out.cols; ++c) {
            const float d = image.data.at<float>(r, c);
            const auto v = static_cast<std::uint8_t>(
                std::isfinite(d) ? std::clamp(d / 2.0f * 255.0f, 0.0f, 255.0f) : 255.0f);
            out.at<cv::Vec3b>(r, c) = {v, v, v};
          }
        break;
      case ImageEncoding::kId32s:
        for (int r = 0; r < out.rows; ++r)
          for (int c = 0; c < out.cols; ++c) {
            const auto v = static_cast<std::uint8_t>(
                (static_cast<unsigned>(image.data.at<std::int32_t>(r, c)) * 37u) % 256u);
            out.at<cv::Vec3b>(r, c) = {v, v, v};
          }
        break;
      case ImageEncoding::kNone:
        break;
    }
    return out;
  }

  const Image* image_;
  VideoEncoder encoder_;
  std::filesystem::path file_;
  cv::Size size_;
  std::uint64_t last_frame_ = 0;
};

}  // namespace

void write_png(const Image& image, const std::filesystem::path& file) {
  if (image.data.empty() || image.encoding == ImageEncoding::kNone)
    throw RunError(fmt::format("image file '{}': the image is empty", file.string()));
  bool ok = false;
  try {
    ok = cv::imwrite(file.string(), png_pixels(image));
  } catch (const cv::Exception& e) {
    throw RunError(fmt::format("image file '{}': {}", file.string(), e.what()));
  }
  if (!ok) throw RunError(fmt::format("image file '{}': cannot be written", file.string()));
}

std::unique_ptr<PortRecorder> make_image_recorder(const Image* image, const RecordTarget& target) {
  if (target.video) return std::make_unique<VideoRecorder>(image, target);
  return std::make_unique<ImageRecorder>(image, target);
}

}  // namespace render
}  // namespace somasim
