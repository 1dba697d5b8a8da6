#include "image_check.hpp"

#include <fmt/format.h>

#include "somasim/error.hpp"

namespace somasim::plugins {

void check_camera_image(const robot::RobotModel& model, const Image& image, const std::string& port,
                        const std::string& camera) {
  const robot::Camera& c = model.cameras()[static_cast<std::size_t>(model.find_camera(camera))];
  if (image.encoding != ImageEncoding::kRgb8)
    throw RunError(fmt::format("input '{}': expected an rgb8 image, got {}", port,
                               image_encoding_name(image.encoding)));
  if (image.data.cols != c.width || image.data.rows != c.height)
    throw RunError(fmt::format(
        "input '{}': the image is {} × {} px, but camera '{}' of robot '{}' is calibrated for "
        "{} × {} px (wire images of that camera at its resolution)",
        port, image.data.cols, image.data.rows, camera, model.name(), c.width, c.height));
  if (!image.camera.empty() && image.camera != camera)
    throw RunError(
        fmt::format("input '{}': the image comes from camera '{}', expected '{}' (param cameras)",
                    port, image.camera, camera));
}

}  // namespace somasim::plugins
