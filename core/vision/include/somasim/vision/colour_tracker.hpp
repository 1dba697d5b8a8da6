#pragma once
/// @file
/// A 2-D tracker of an object's colour distribution in one camera's images: a hue-saturation
/// histogram taken at acquisition (from a region known to be the object, e.g. a moving blob),
/// cv::calcBackProject + cv::CamShift per frame; lost when the back-projection mass in the
/// search window collapses (the object left, was removed or hidden).
///
/// Images are rgb8 (CV_8UC3, R G B; pixel conventions of somasim/render/camera.hpp). HSV follows
/// OpenCV's 8-bit convention (hue 0-179, saturation and value 0-255). Pixels below
/// `min_saturation` or `min_value` carry no reliable hue (grey, white, dark) and are ignored.
/// Bins that the background holds as much as the object are weakened at acquisition (the
/// object's histogram is divided by the image's), so a textured backdrop of other colours does
/// not pull the window away.
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include <Eigen/Core>

namespace somasim::vision {

struct ColourTrackerOptions {
  int hue_bins = 30;          ///< over hue 0-179
  int saturation_bins = 16;   ///< over saturation 0-255
  int min_saturation = 60;    ///< pixels below carry no colour
  int min_value = 30;         ///< darker pixels carry no colour
  int min_object_px = 12;     ///< fewest coloured pixels for an acquisition or a tracked frame
  double object_level = 0.3;  ///< a pixel is the object's where the back-projection >= this
                              ///< fraction of its maximum (255)
  /// Lost when the object's pixels in the window fall below this fraction of their running
  /// mean over the tracked frames (a collapse, not a slow change of size).
  double lost_fraction = 0.3;
  /// An acquisition is refused when the acquired colours are not the object's own: pixels of
  /// those colours (back-projection >= object_level) outside the region (dilated by a quarter
  /// of its size) exceed this multiple of those inside it — a moving blob that only holds
  /// colours of the static backdrop or robot (e.g. the whole image after a jump of the scene,
  /// or the flow's fringe around a hand) would lock on to static clutter.
  double max_background_ratio = 1.0;
  /// The robot's own colours (rgb8, e.g. its rendered skin): an acquisition whose colour mode
  /// (the best hue-saturation bin) lies within one bin of one of them is refused — the robot's
  /// own moving hand is not an object. Colours below min_saturation / min_value carry no hue
  /// and are ignored.
  std::vector<cv::Vec3b> own_colours;
  int max_iterations = 10;  ///< CamShift iterations
  double epsilon_px = 0.5;  ///< CamShift stops when the window moves less [px]
};

/// The object in one image.
struct ColourTrack {
  bool tracked = false;
  Eigen::Vector2d centre_px = Eigen::Vector2d::Zero();  ///< centroid of its pixels (u, v) [px]
  /// sqrt(area / π) of its pixels: the radius of a disc of the same area [px].
  double radius_px = 0.0;
  int object_px = 0;    ///< pixels at or above object_level in the window
  cv::RotatedRect box;  ///< CamShift's oriented box [px]
  cv::Rect window;      ///< the search window for the next frame [px]
};

/// Why the last acquire() returned false.
enum class Refusal : std::uint8_t {
  kNone,            ///< acquired
  kTooFew,          ///< fewer than min_object_px coloured pixels in the region
  kNotDistinctive,  ///< the colours are as common elsewhere (max_background_ratio)
  kOwnColour,       ///< the colour mode is one of own_colours
};

class ColourTracker {
 public:
  /// Throws somasim::InputError "ColourTracker: <option>: expected ..., got N" for bins outside
  /// [1, 180] / [1, 256], levels outside [0, 255], fractions outside (0, 1), counts < 1 or a
  /// max_background_ratio <= 0.
  explicit ColourTracker(const ColourTrackerOptions& options = {});

  /// Takes the object's colour histogram from the pixels of `rgb` where `object_mask` (CV_8U,
  /// image size) is non-zero, and starts tracking in the mask's bounding box. Returns false
  /// (and does not track) when the mask holds fewer than min_object_px coloured pixels, the
  /// colours are not distinctive (max_background_ratio) or are the robot's own (own_colours);
  /// last_refusal() says which.
  /// InputError "ColourTracker: expected an rgb8 image (CV_8UC3) and a CV_8U mask of its
  /// size, got ..." for other images.
  bool acquire(const cv::Mat& rgb, const cv::Mat& object_mask);
  /// One CamShift step in `rgb` (same size as at acquisition, else InputError naming both
  /// sizes). Not tracked (and no longer tracking) when the object collapsed; nothing to do
  /// when not tracking.
  ColourTrack track(const cv::Mat& rgb);
  /// Moves the search window's centre by the homography `h` (previous image -> this one, e.g.
  /// the camera's own rotation between the frames), keeping its size: where the object is
  /// expected before the next track(). Nothing to do when not tracking.
  void shift_window(const cv::Matx33d& h);
  /// Stops tracking (the next acquire() starts afresh).
  void lose() { tracking_ = false; }

  bool tracking() const { return tracking_; }
  /// The acquired hue-saturation histogram (CV_32F, hue_bins × saturation_bins, maximum 255);
  /// empty before the first acquisition.
  const cv::Mat& histogram() const { return histogram_; }
  /// Why the last acquire() failed (kNone after a success or before any).
  Refusal last_refusal() const { return refusal_; }
  /// The back-projection (CV_8U, 0-255) of `rgb` through the acquired histogram; empty before.
  cv::Mat back_projection(const cv::Mat& rgb) const;

 private:
  cv::Mat hsv_and_mask(const cv::Mat& rgb, cv::Mat& coloured) const;
  ColourTrackerOptions options_;
  cv::Mat histogram_;  // CV_32F, hue_bins × saturation_bins, scaled to a maximum of 255
  cv::Size size_;
  cv::Rect window_;
  double mean_object_px_ = 0.0;
  int frames_ = 0;
  bool tracking_ = false;
  Refusal refusal_ = Refusal::kNone;
  std::vector<cv::Point> own_bins_;  // (saturation bin, hue bin) of own_colours
};

/// Bhattacharyya distance of two trackers' colour models (cv::HISTCMP_BHATTACHARYYA): 0 for
/// the same histogram, 1 for disjoint ones; 1 when either has acquired nothing.
double colour_distance(const ColourTracker& a, const ColourTracker& b);

}  // namespace somasim::vision
