#pragma once
/// @file
/// The StereoPixels port type: where a tracked marker appears in the two eyes' images.
///
/// Pixel positions (u, v) follow somasim/render/camera.hpp (u right, v down, pixel centres at
/// integers). A recorded port writes one CSV row per step: found flags, positions [px] and blob
/// areas [px] of both eyes (NaN positions where not found).
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "somasim/port_type.hpp"

namespace somasim {

struct StereoPixels {
  struct Eye {
    /// This image's blob is the marker's (part of the stereo-consistent pair the tracker took);
    /// when false the fields show the image's largest blob of the colour, if any (area 0: none).
    bool found = false;
    Eigen::Vector2d uv_px = Eigen::Vector2d::Zero();      ///< the blob's centroid [px]
    Eigen::Vector2d circle_px = Eigen::Vector2d::Zero();  ///< centre of its enclosing circle [px]
    int area_px = 0;                                      ///< the blob's pixels
  };
  Eye left;                 ///< the tracker's first camera
  Eye right;                ///< its second camera
  std::uint64_t frame = 0;  ///< the left image's frame number these come from (0 = none yet)
};

template <>
struct PortTraits<StereoPixels> {
  static constexpr const char* name = "stereo_pixels";
  static constexpr const char* header = "somasim/vision/ports.hpp";
  static std::vector<std::string> csv_columns(const StereoPixels&) {
    return {"left found",  "left u [px]",  "left v [px]",  "left area [px]",
            "right found", "right u [px]", "right v [px]", "right area [px]"};
  }
  static void csv_write(const StereoPixels& p, std::string& row) {
    for (const StereoPixels::Eye* e : {&p.left, &p.right}) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      csv_append(row, e->found ? 1.0 : 0.0);
      csv_append(row, e->found ? e->uv_px.x() : nan);
      csv_append(row, e->found ? e->uv_px.y() : nan);
      csv_append(row, static_cast<double>(e->area_px));
    }
  }
};

}  // namespace somasim
