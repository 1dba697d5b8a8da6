#pragma once
/// @file
/// The image port types: a cv::Mat-backed camera image with its encoding and frame. One port
/// type per encoding (RgbImage, DepthImage, LabelImage), so that wiring a depth output to an
/// input that expects colour is refused when the experiment is checked; all three are an Image.
///
/// Encodings (`data` is `height` rows × `width` columns, row 0 = top of the image, pixel
/// conventions of camera.hpp):
///   - kRgb8:    CV_8UC3, channels R, G, B;
///   - kDepth32f: CV_32F, metres along the camera's z axis (optical axis), 0 = nothing drawn;
///   - kId32s:   CV_32S, the id of what is seen (render/robot_scene.hpp: link i -> i + 1,
///               object k -> 1000 + k; 0 = background).
///
/// Recording an Image port (`record: [cam.left_eye_rgb]`) writes PNGs into the folder
/// `NODE.PORT/` of the run folder, one per new frame, named `FRAME.png` (FRAME = the image's
/// `frame` number, 6 digits), plus `NODE.PORT/index.csv` (time [s], frame, file). PNG encodings
/// (write_png): rgb8 -> 8-bit RGB; depth32f -> 16-bit grey in millimetres (rounded, 0 = nothing,
/// clamped to 65535 mm); id32s -> 16-bit grey of the ids (clamped to 65535).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "somasim/port_type.hpp"

namespace somasim {

enum class ImageEncoding : std::uint8_t { kNone = 0, kRgb8, kDepth32f, kId32s };

/// "rgb8", "depth32f", "id32s" ("none" for kNone).
const char* image_encoding_name(ImageEncoding encoding);

struct Image {
  cv::Mat data;  ///< see the file comment; empty before the first frame
  ImageEncoding encoding = ImageEncoding::kNone;
  std::string camera;       ///< the robot model's camera that saw it (its frame: camera.hpp)
  double time_s = 0.0;      ///< sim time at which the scene was rendered [s]
  std::uint64_t frame = 0;  ///< 1, 2, ... per producer and port; 0 = no image yet
};

namespace render {
/// Writes `image` as a PNG (encodings in the file comment). Throws somasim::RunError naming
/// the file when it cannot be written or the image is empty.
void write_png(const Image& image, const std::filesystem::path& file);
/// The PNG recorder of an Image port (see the file comment).
std::unique_ptr<PortRecorder> make_image_recorder(const Image* image, const RecordTarget& target);
}  // namespace render

namespace detail {
/// What the three image port types share: copying and the PNG (or video) recorder.
struct ImagePortTraits {
  static constexpr const char* header = "somasim/render/ports.hpp";
  static constexpr bool records_video = true;
  static void copy(Image& dst, const Image& src) {
    src.data.copyTo(dst.data);
    dst.encoding = src.encoding;
    dst.camera = src.camera;
    dst.time_s = src.time_s;
    dst.frame = src.frame;
  }
  static std::unique_ptr<PortRecorder> recorder(const Image* image, const RecordTarget& target) {
    return render::make_image_recorder(image, target);
  }
};
}  // namespace detail

/// A colour image port: encoding kRgb8 (or kNone before the first frame).
struct RgbImage : Image {};
/// A depth image port: encoding kDepth32f [m] (or kNone before the first frame).
struct DepthImage : Image {};
/// An id-mask image port: encoding kId32s (or kNone before the first frame).
struct LabelImage : Image {};

template <>
struct PortTraits<RgbImage> : detail::ImagePortTraits {
  static constexpr const char* name = "rgb8_image";
};
template <>
struct PortTraits<DepthImage> : detail::ImagePortTraits {
  static constexpr const char* name = "depth32f_image";
};
template <>
struct PortTraits<LabelImage> : detail::ImagePortTraits {
  static constexpr const char* name = "id32s_image";
};

}  // namespace somasim
