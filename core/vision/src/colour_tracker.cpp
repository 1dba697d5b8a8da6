#include "somasim/vision/colour_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "somasim/error.hpp"
#include "somasim/numeric.hpp"

namespace somasim::vision {
namespace {

constexpr double kMeanWeight = 0.2;     // of the newest frame in the running mean of the size
constexpr double kModeFraction = 0.05;  // of the best bin's score: the object's colour mode

void check(bool ok, const char* option, const std::string& expected, double value) {
  if (!ok)
    throw InputError(
        fmt::format("ColourTracker: {}: expected {}, got {}", option, expected, value));
}

std::string describe(const cv::Mat& m) {
  if (m.empty()) return "an empty image";
  return fmt::format("{} {} × {}", cv::typeToString(m.type()), m.cols, m.rows);
}

}  // namespace

ColourTracker::ColourTracker(const ColourTrackerOptions& options) : options_(options) {
  const auto& o = options;
  check(o.hue_bins >= 1 && o.hue_bins <= 180, "hue_bins", "1 to 180", o.hue_bins);
  check(o.saturation_bins >= 1 && o.saturation_bins <= 256, "saturation_bins", "1 to 256",
        o.saturation_bins);
  check(o.min_saturation >= 0 && o.min_saturation <= 255, "min_saturation", "0 to 255",
        o.min_saturation);
  check(o.min_value >= 0 && o.min_value <= 255, "min_value", "0 to 255", o.min_value);
  check(o.min_object_px >= 1, "min_object_px", ">= 1", o.min_object_px);
  check(o.object_level > 0 && o.object_level < 1, "object_level", "a fraction in (0, 1)",
        o.object_level);
  check(o.lost_fraction > 0 && o.lost_fraction < 1, "lost_fraction", "a fraction in (0, 1)",
        o.lost_fraction);
  check(o.max_background_ratio > 0, "max_background_ratio", "> 0", o.max_background_ratio);
  check(o.max_iterations >= 1, "max_iterations", ">= 1", o.max_iterations);
  check(o.epsilon_px > 0, "epsilon_px", "> 0", o.epsilon_px);
  for (const cv::Vec3b& rgb : o.own_colours) {
    cv::Mat hsv;
    cv::cvtColor(cv::Mat(1, 1, CV_8UC3, cv::Scalar(rgb[0], rgb[1], rgb[2])), hsv,
                 cv::COLOR_RGB2HSV);
    const cv::Vec3b v = hsv.at<cv::Vec3b>(0, 0);
    if (v[1] < o.min_saturation || v[2] < o.min_value) continue;  // no hue
    own_bins_.emplace_back(v[1] * o.saturation_bins / 256, v[0] * o.hue_bins / 180);
  }
}

cv::Mat ColourTracker::hsv_and_mask(const cv::Mat& rgb, cv::Mat& coloured) const {
  cv::Mat hsv;
  cv::cvtColor(rgb, hsv, cv::COLOR_RGB2HSV);
  cv::inRange(hsv, cv::Scalar(0, options_.min_saturation, options_.min_value),
              cv::Scalar(180, 255, 255), coloured);
  return hsv;
}

bool ColourTracker::acquire(const cv::Mat& rgb, const cv::Mat& object_mask) {
  if (rgb.empty() || rgb.type() != CV_8UC3 || object_mask.type() != CV_8U ||
      object_mask.size() != rgb.size())
    throw InputError(fmt::format(
        "ColourTracker: expected an rgb8 image (CV_8UC3) and a CV_8U mask of its size, got {} "
        "and {}",
        describe(rgb), describe(object_mask)));
  tracking_ = false;
  refusal_ = Refusal::kTooFew;
  cv::Mat coloured;
  const cv::Mat hsv = hsv_and_mask(rgb, coloured);
  const cv::Mat object = coloured & (object_mask != 0);
  const int object_px = cv::countNonZero(object);
  if (object_px < options_.min_object_px) return false;

  const int channels[] = {0, 1};
  const int bins[] = {options_.hue_bins, options_.saturation_bins};
  const float hue_range[] = {0, 180};
  const float saturation_range[] = {0, 256};
  const float* ranges[] = {hue_range, saturation_range};
  cv::Mat in_object, in_image;
  cv::calcHist(&hsv, 1, channels, object, in_object, 2, bins, ranges);
  cv::calcHist(&hsv, 1, channels, coloured, in_image, 2, bins, ranges);
  // Each bin scored by its pixels in the region times the region's share of the bin's pixels
  // in the image (P(region | colour)). The object is the region's dominant colour mode: the
  // bins connected (8-neighbours, hue cyclic) to the best one whose score is at least
  // kModeFraction of the best. Other colours in the region (the backdrop around and behind the
  // moving object, which the flow's smoothing includes) are dropped. The kept bins weigh by
  // P(region | colour).
  cv::Mat score = cv::Mat::zeros(in_object.size(), CV_32F);
  cv::Mat share = cv::Mat::zeros(in_object.size(), CV_32F);
  for (int h = 0; h < in_object.rows; ++h)
    for (int s = 0; s < in_object.cols; ++s) {
      const float n = in_object.at<float>(h, s);
      if (n <= 0) continue;
      share.at<float>(h, s) = n / std::max(1.0F, in_image.at<float>(h, s));
      score.at<float>(h, s) = n * share.at<float>(h, s);
    }
  double best = 0.0;
  cv::Point best_at;
  cv::minMaxLoc(score, nullptr, &best, nullptr, &best_at);
  for (const cv::Point& own : own_bins_) {  // (x: saturation bin, y: hue bin); hue cyclic
    const int dh = std::abs(own.y - best_at.y);
    if (std::min(dh, options_.hue_bins - dh) <= 1 && std::abs(own.x - best_at.x) <= 1) {
      refusal_ = Refusal::kOwnColour;
      return false;
    }
  }
  histogram_ = cv::Mat::zeros(in_object.size(), CV_32F);
  std::vector<cv::Point> open = {best_at};  // (x: saturation bin, y: hue bin)
  histogram_.at<float>(best_at) = share.at<float>(best_at);
  while (!open.empty()) {
    const cv::Point at = open.back();
    open.pop_back();
    for (int dh = -1; dh <= 1; ++dh)
      for (int ds = -1; ds <= 1; ++ds) {
        const int h = (at.y + dh + score.rows) % score.rows;
        const int sat = at.x + ds;
        if (sat < 0 || sat >= score.cols || histogram_.at<float>(h, sat) > 0 ||
            score.at<float>(h, sat) < kModeFraction * best)
          continue;
        histogram_.at<float>(h, sat) = share.at<float>(h, sat);
        open.emplace_back(sat, h);
      }
  }
  cv::normalize(histogram_, histogram_, 0, 255, cv::NORM_MINMAX);
  // The window: the region's pixels of the kept colours.
  cv::Mat kept;
  cv::calcBackProject(&hsv, 1, channels, histogram_, kept, ranges);
  const cv::Mat object_kept = object & (kept > 0);
  // Distinctive colours only: the object's colours elsewhere in the image (beyond the region
  // grown by a quarter of its size) must not outweigh those in it.
  const cv::Mat strong = (kept >= 255.0 * options_.object_level) & coloured;
  const cv::Rect box = cv::boundingRect(object_kept);
  const int grow = std::max(2, std::max(box.width, box.height) / 4);
  cv::Mat near_object;
  cv::dilate(object_mask != 0, near_object,
             cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * grow + 1, 2 * grow + 1)));
  const int inside = cv::countNonZero(strong & near_object);
  const int outside = cv::countNonZero(strong) - inside;
  if (inside < options_.min_object_px || outside > options_.max_background_ratio * inside) {
    refusal_ = Refusal::kNotDistinctive;
    return false;
  }
  refusal_ = Refusal::kNone;
  size_ = rgb.size();
  window_ = cv::boundingRect(object_kept);
  mean_object_px_ = 0.0;
  frames_ = 0;
  tracking_ = true;
  return true;
}

void ColourTracker::shift_window(const cv::Matx33d& h) {
  if (!tracking_) return;
  const double cx = window_.x + 0.5 * window_.width;
  const double cy = window_.y + 0.5 * window_.height;
  const cv::Vec3d c = h * cv::Vec3d(cx, cy, 1.0);
  if (std::abs(c[2]) < 1e-12) return;
  // Far outside the image the window finds nothing either way; held where an int holds it.
  constexpr int kFar = 1 << 20;  // [px]
  window_.x = to_integer_clamped<int>(c[0] / c[2] - 0.5 * window_.width, -kFar, kFar);
  window_.y = to_integer_clamped<int>(c[1] / c[2] - 0.5 * window_.height, -kFar, kFar);
}

cv::Mat ColourTracker::back_projection(const cv::Mat& rgb) const {
  if (histogram_.empty()) return {};
  cv::Mat coloured;
  const cv::Mat hsv = hsv_and_mask(rgb, coloured);
  const int channels[] = {0, 1};
  const float hue_range[] = {0, 180};
  const float saturation_range[] = {0, 256};
  const float* ranges[] = {hue_range, saturation_range};
  cv::Mat bp;
  cv::calcBackProject(&hsv, 1, channels, histogram_, bp, ranges);
  bp.setTo(0, coloured == 0);
  return bp;
}

ColourTrack ColourTracker::track(const cv::Mat& rgb) {
  ColourTrack out;
  if (!tracking_) return out;
  if (rgb.empty() || rgb.type() != CV_8UC3 || rgb.size() != size_)
    throw InputError(
        fmt::format("ColourTracker: expected an rgb8 image (CV_8UC3) of {} × {} (the size at "
                    "acquisition), got {}",
                    size_.width, size_.height, describe(rgb)));
  const cv::Mat bp = back_projection(rgb);
  window_ &= cv::Rect(0, 0, size_.width, size_.height);
  if (window_.area() < 1) return lose(), out;
  out.box = cv::CamShift(bp, window_,
                         cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT,
                                          options_.max_iterations, options_.epsilon_px));
  window_ &= cv::Rect(0, 0, size_.width, size_.height);
  out.window = window_;
  if (window_.area() < 1) return lose(), out;
  // The object's pixels in the window with a margin (CamShift's box is the distribution's
  // ellipse, a little tighter than a disc's edge): count, centroid.
  const int margin = std::max(3, std::max(window_.width, window_.height) / 4);
  const cv::Rect counted = cv::Rect(window_.x - margin, window_.y - margin,
                                    window_.width + 2 * margin, window_.height + 2 * margin) &
                           cv::Rect(0, 0, size_.width, size_.height);
  const cv::Mat object = bp(counted) >= 255.0 * options_.object_level;
  const cv::Moments m = cv::moments(object, /*binaryImage=*/true);
  out.object_px = static_cast<int>(std::lround(m.m00));
  const bool collapsed = out.object_px < options_.min_object_px ||
                         (frames_ > 0 && out.object_px < options_.lost_fraction * mean_object_px_);
  if (collapsed) return lose(), out;
  mean_object_px_ = frames_ == 0
                        ? out.object_px
                        : (1 - kMeanWeight) * mean_object_px_ + kMeanWeight * out.object_px;
  ++frames_;
  out.tracked = true;
  out.centre_px = {counted.x + m.m10 / m.m00, counted.y + m.m01 / m.m00};
  out.radius_px = std::sqrt(m.m00 / CV_PI);
  return out;
}

double colour_distance(const ColourTracker& a, const ColourTracker& b) {
  if (a.histogram().empty() || b.histogram().empty() ||
      a.histogram().size() != b.histogram().size())
    return 1.0;
  return cv::compareHist(a.histogram(), b.histogram(), cv::HISTCMP_BHATTACHARYYA);
}

}  // namespace somasim::vision
