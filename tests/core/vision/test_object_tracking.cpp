// The generic object tracker's 2-D pieces on synthetic images: a red disc moving over a textured
// background. Motion detection by optical flow (also with the whole image shifting, as when the
// head turns), acquisition of the disc's colour histogram from the moving blob, CamShift
// tracking, loss when the disc is removed and re-acquisition by motion.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include <Eigen/Geometry>

#include <opencv2/imgproc.hpp>

#include "somasim/error.hpp"
#include "somasim/vision/colour_tracker.hpp"
#include "somasim/vision/motion_detection.hpp"

namespace vision = somasim::vision;

namespace {

constexpr int kWidth = 320, kHeight = 240;

// A textured backdrop: 60 rectangles of random colours (none saturated red, the disc's hue
// range) on grey, larger than the image so that it can be shifted.
cv::Mat backdrop(int margin = 0, std::uint64_t backdrop_seed = 5) {
  cv::Mat image(kHeight + 2 * margin, kWidth + 2 * margin, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::RNG rng(backdrop_seed);
  for (int i = 0; i < 60; ++i) {
    const int x = rng.uniform(0, image.cols), y = rng.uniform(0, image.rows);
    const int w = rng.uniform(10, 60), h = rng.uniform(10, 60);
    // One draw per statement: the order of evaluation of function arguments is unspecified
    // (g++ and clang++ drew different backdrops).
    const int hue = rng.uniform(20, 160);
    const int saturation = rng.uniform(0, 255);
    const int value = rng.uniform(40, 255);
    cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue, saturation, value));
    cv::Mat rgb;
    cv::cvtColor(hsv, rgb, cv::COLOR_HSV2RGB);
    cv::rectangle(image, cv::Rect(x, y, w, h), cv::Scalar(rgb.at<cv::Vec3b>(0, 0)), cv::FILLED);
  }
  return image;
}

// The backdrop (shifted by `shift` px) with a red disc centred at `centre` [px].
cv::Mat scene(const cv::Mat& background, const Eigen::Vector2d& centre, double radius,
              const cv::Point& shift = {0, 0}, int margin = 0) {
  cv::Mat image = background(cv::Rect(margin - shift.x, margin - shift.y, kWidth, kHeight)).clone();
  if (radius > 0) {
    constexpr int kShift = 4;  // sub-pixel drawing: coordinates × 16
    cv::circle(image,
               cv::Point(static_cast<int>(std::lround(centre.x() * 16)),
                         static_cast<int>(std::lround(centre.y() * 16))),
               static_cast<int>(std::lround(radius * 16)), cv::Scalar(220, 30, 25), cv::FILLED,
               cv::LINE_AA, kShift);
  }
  return image;
}

Eigen::Vector2d path(int frame) {
  return {80.0 + 3.0 * frame, 70.0 + 1.5 * frame};  // 3.4 px per frame
}

}  // namespace

TEST(MotionDetection, StillImagesHaveNoMotion) {
  const cv::Mat bg = backdrop();
  const cv::Mat a = scene(bg, path(0), 12);
  EXPECT_FALSE(vision::detect_motion(a, a).found);
}

TEST(MotionDetection, TheMovingDiscIsTheLargestMovingBlob) {
  const cv::Mat bg = backdrop();
  const vision::MotionBlob m =
      vision::detect_motion(scene(bg, path(0), 12), scene(bg, path(1), 12));
  ASSERT_TRUE(m.found);
  // The blob covers the disc (and a little of where it was), not much more.
  EXPECT_LT((m.centroid_px - path(1)).norm(), 4.0) << m.centroid_px.transpose();
  EXPECT_TRUE(
      m.box.contains(cv::Point(static_cast<int>(path(1).x()), static_cast<int>(path(1).y()))));
  EXPECT_GT(m.area_px, 200);  // the disc: 452 px
  EXPECT_LT(m.area_px, 2000);
  EXPECT_GT(m.mean_flow_px.x(), 1.0);  // it moved right and down
  EXPECT_GT(m.mean_flow_px.y(), 0.3);
  EXPECT_EQ(m.mask.at<unsigned char>(static_cast<int>(path(1).y()), static_cast<int>(path(1).x())),
            255);
}

// The camera turns: the backdrop shifts by (4, -2) px while the disc moves. Given the
// ego-motion's homography the moving blob is the disc (with the background it uncovered: the
// blob spans where the disc was and is); without it, the textured backdrop moves. Over several
// backdrops (one of them once gave a blob on the uncovered part only, 8.8 px from the disc).
TEST(MotionDetection, EgoMotionHomographyIsCompensated) {
  constexpr int kMargin = 20;
  const cv::Matx33d shift(1, 0, 4, 0, 1, -2, 0, 0, 1);
  for (std::uint64_t seed = 5; seed < 10; ++seed) {
    const cv::Mat bg = backdrop(kMargin, seed);
    const cv::Mat a = scene(bg, path(0), 12, {0, 0}, kMargin);
    const cv::Mat b = scene(bg, path(2), 12, {4, -2}, kMargin);
    const vision::MotionBlob m = vision::detect_motion(a, b, {}, shift);
    ASSERT_TRUE(m.found) << "backdrop " << seed;
    // Between the disc now (path(2)) and where the background put it before (path(0) + shift).
    const Eigen::Vector2d before = path(0) + Eigen::Vector2d(4, -2);
    EXPECT_LT((m.centroid_px - path(2)).norm(), 12.0) << "backdrop " << seed;
    EXPECT_LT((m.centroid_px - before).norm(), 12.0) << "backdrop " << seed;
    EXPECT_LT(m.area_px, 2500) << "backdrop " << seed;
    EXPECT_GT(vision::detect_motion(a, b).area_px, 5000) << "backdrop " << seed;
  }
  // A camera turned by 1° about its vertical axis: the homography is a shift of f tan(1°) px
  // near the centre.
  const Eigen::Matrix3d turned =
      Eigen::AngleAxisd(0.01745329, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const cv::Matx33d h = vision::rotation_homography(Eigen::Matrix3d::Identity(), turned, 257.34,
                                                    257.34, 159.5, 119.5);
  const cv::Vec3d centre = h * cv::Vec3d(159.5, 119.5, 1);
  EXPECT_NEAR(centre[0] / centre[2] - 159.5, -257.34 * std::tan(0.01745329), 1e-6);
  EXPECT_NEAR(centre[1] / centre[2], 119.5, 1e-9);
}

TEST(MotionDetection, BadInputsAreClearErrors) {
  const cv::Mat a(240, 320, CV_8UC3, cv::Scalar::all(0));
  const cv::Mat b(120, 160, CV_8UC3, cv::Scalar::all(0));
  const cv::Mat grey(240, 320, CV_8U, cv::Scalar::all(0));
  try {
    vision::detect_motion(a, b);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "detect_motion: expected two rgb8 images (CV_8UC3) of one size, got CV_8UC3 "
                 "320 × 240 and CV_8UC3 160 × 120");
  }
  try {
    vision::detect_motion(grey, cv::Mat());
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "detect_motion: expected two rgb8 images (CV_8UC3) of one size, got CV_8UC1 "
                 "320 × 240 and an empty image");
  }
  vision::MotionOptions o;
  o.min_area_px = 0;
  try {
    vision::detect_motion(a, a, o);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(), "detect_motion: min_area_px: expected >= 1, got 0");
  }
}

// Acquired from the moving blob, CamShift follows the disc for 30 frames within a pixel; the
// radius of the disc of the same area within 10 %.
TEST(ColourTracker, FollowsTheDiscAcquiredByMotion) {
  const cv::Mat bg = backdrop();
  vision::ColourTracker tracker;
  const cv::Mat first = scene(bg, path(1), 12);
  const vision::MotionBlob m = vision::detect_motion(scene(bg, path(0), 12), first);
  ASSERT_TRUE(m.found);
  ASSERT_TRUE(tracker.acquire(first, m.mask));
  double worst = 0;
  for (int k = 1; k <= 30; ++k) {
    const vision::ColourTrack t = tracker.track(scene(bg, path(k), 12));
    ASSERT_TRUE(t.tracked) << "frame " << k;
    worst = std::max(worst, (t.centre_px - path(k)).norm());
    EXPECT_NEAR(t.radius_px, 12.0, 1.2) << "frame " << k;
  }
  EXPECT_LT(worst, 1.0);
  EXPECT_TRUE(tracker.tracking());
}

// The disc is removed: lost at once (not stuck on the backdrop); it reappears elsewhere and
// moves: motion finds it again and the tracker follows it there.
TEST(ColourTracker, LossAndReacquisition) {
  const cv::Mat bg = backdrop();
  vision::ColourTracker tracker;
  const vision::MotionBlob m =
      vision::detect_motion(scene(bg, path(0), 12), scene(bg, path(1), 12));
  ASSERT_TRUE(tracker.acquire(scene(bg, path(1), 12), m.mask));
  for (int k = 1; k <= 5; ++k) ASSERT_TRUE(tracker.track(scene(bg, path(k), 12)).tracked);
  const cv::Mat empty = scene(bg, path(6), 0);
  EXPECT_FALSE(tracker.track(empty).tracked);
  EXPECT_FALSE(tracker.tracking());
  EXPECT_FALSE(tracker.track(empty).tracked);  // stays lost
  // Back at another place, moving left.
  const auto elsewhere = [](int k) { return Eigen::Vector2d(250.0 - 2.5 * k, 180.0); };
  EXPECT_FALSE(vision::detect_motion(empty, empty).found);
  const cv::Mat shown = scene(bg, elsewhere(0), 10);
  const cv::Mat moved = scene(bg, elsewhere(1), 10);
  const vision::MotionBlob again = vision::detect_motion(shown, moved);
  ASSERT_TRUE(again.found);
  ASSERT_TRUE(tracker.acquire(moved, again.mask));
  for (int k = 2; k <= 10; ++k) {
    const vision::ColourTrack t = tracker.track(scene(bg, elsewhere(k), 10));
    ASSERT_TRUE(t.tracked) << "frame " << k;
    EXPECT_LT((t.centre_px - elsewhere(k)).norm(), 1.0) << "frame " << k;
  }
}

// Half of the disc hidden behind a grey bar for a frame: still tracked (a partial occlusion is
// no collapse), the centre pulled toward the visible half.
TEST(ColourTracker, PartialOcclusionIsNoLoss) {
  const cv::Mat bg = backdrop();
  vision::ColourTracker tracker;
  const vision::MotionBlob m =
      vision::detect_motion(scene(bg, path(0), 12), scene(bg, path(1), 12));
  ASSERT_TRUE(tracker.acquire(scene(bg, path(1), 12), m.mask));
  for (int k = 1; k <= 5; ++k) ASSERT_TRUE(tracker.track(scene(bg, path(k), 12)).tracked);
  cv::Mat hidden = scene(bg, path(6), 12);
  cv::rectangle(hidden, cv::Rect(static_cast<int>(path(6).x()), 0, 40, kHeight),
                cv::Scalar(128, 128, 128), cv::FILLED);
  const vision::ColourTrack t = tracker.track(hidden);
  EXPECT_TRUE(t.tracked);
  EXPECT_LT(t.centre_px.x(), path(6).x() - 3.0);
}

TEST(ColourTracker, AcquisitionNeedsColouredPixels) {
  const cv::Mat grey(kHeight, kWidth, CV_8UC3, cv::Scalar::all(128));
  cv::Mat mask = cv::Mat::zeros(kHeight, kWidth, CV_8U);
  mask(cv::Rect(100, 100, 20, 20)).setTo(255);
  vision::ColourTracker tracker;
  EXPECT_FALSE(tracker.acquire(grey, mask));  // no hue in grey
  EXPECT_FALSE(tracker.tracking());
  EXPECT_FALSE(tracker.track(grey).tracked);
}

// A moving blob whose colour is found all over the image (here four more red discs like the
// object on the backdrop) is not acquired: the tracker would lock on to static clutter. The same
// blob on the backdrop without them is.
TEST(ColourTracker, AcquisitionOfColoursTheBackdropHoldsIsRefused) {
  const cv::Mat bg = backdrop();
  cv::Mat cluttered = bg.clone();
  for (int i = 0; i < 4; ++i)
    cv::circle(cluttered, cv::Point(40 + 70 * i, 200), 14, cv::Scalar(220, 30, 25), cv::FILLED);
  cv::Mat mask = cv::Mat::zeros(kHeight, kWidth, CV_8U);
  cv::circle(mask, cv::Point(120, 100), 11, cv::Scalar(255), cv::FILLED);  // the disc only
  vision::ColourTracker tracker;
  EXPECT_FALSE(tracker.acquire(scene(cluttered, {120, 100}, 12), mask));
  EXPECT_FALSE(tracker.tracking());
  EXPECT_TRUE(tracker.acquire(scene(bg, {120, 100}, 12), mask));
  vision::ColourTrackerOptions lenient;  // four larger discs elsewhere: ~5× the blob's pixels
  lenient.max_background_ratio = 8.0;
  EXPECT_TRUE(vision::ColourTracker(lenient).acquire(scene(cluttered, {120, 100}, 12), mask));
}

TEST(ColourTracker, BadInputsAreClearErrors) {
  vision::ColourTrackerOptions o;
  o.hue_bins = 0;
  try {
    vision::ColourTracker t(o);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(), "ColourTracker: hue_bins: expected 1 to 180, got 0");
  }
  o = {};
  o.lost_fraction = 1.5;
  try {
    vision::ColourTracker t(o);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(), "ColourTracker: lost_fraction: expected a fraction in (0, 1), got 1.5");
  }
  o = {};
  o.max_background_ratio = 0;
  try {
    vision::ColourTracker t(o);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(), "ColourTracker: max_background_ratio: expected > 0, got 0");
  }
  const cv::Mat bg = backdrop();
  vision::ColourTracker tracker;
  const cv::Mat a = scene(bg, path(0), 12);
  try {
    tracker.acquire(a, cv::Mat::zeros(10, 10, CV_8U));
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "ColourTracker: expected an rgb8 image (CV_8UC3) and a CV_8U mask of its size, "
                 "got CV_8UC3 320 × 240 and CV_8UC1 10 × 10");
  }
  const vision::MotionBlob m = vision::detect_motion(a, scene(bg, path(1), 12));
  ASSERT_TRUE(tracker.acquire(scene(bg, path(1), 12), m.mask));
  try {
    tracker.track(cv::Mat(480, 640, CV_8UC3, cv::Scalar::all(0)));
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "ColourTracker: expected an rgb8 image (CV_8UC3) of 320 × 240 (the size at "
                 "acquisition), got CV_8UC3 640 × 480");
  }
}

// The robot's own colours (own_colours, e.g. its rendered skin) are not an object: a moving blob
// of one of them is refused (last_refusal: kOwnColour); the same blob is acquired when the
// robot's colours are others.
TEST(ColourTracker, AcquisitionOfTheRobotsOwnColourIsRefused) {
  const cv::Mat bg = backdrop();
  cv::Mat mask = cv::Mat::zeros(kHeight, kWidth, CV_8U);
  cv::circle(mask, cv::Point(120, 100), 11, cv::Scalar(255), cv::FILLED);
  vision::ColourTrackerOptions own;
  own.own_colours.emplace_back(237, 189, 153);  // skin
  own.own_colours.emplace_back(200, 30, 26);    // a darker red
  vision::ColourTracker tracker(own);
  EXPECT_FALSE(tracker.acquire(scene(bg, {120, 100}, 12), mask));
  EXPECT_EQ(tracker.last_refusal(), vision::Refusal::kOwnColour);
  EXPECT_FALSE(tracker.tracking());
  own.own_colours.back() = cv::Vec3b(25, 200, 40);  // green instead
  vision::ColourTracker other(own);
  EXPECT_TRUE(other.acquire(scene(bg, {120, 100}, 12), mask));
  EXPECT_EQ(other.last_refusal(), vision::Refusal::kNone);
}

// The whole image jumps by 60 px (the head turned between two frames) while the disc stays on
// the backdrop: the search window moved by the known turn (shift_window) still finds the disc;
// left where it was, it finds nothing there and the track is lost.
TEST(ColourTracker, TheSearchWindowFollowsTheCamerasOwnTurn) {
  constexpr int kMargin = 80;
  const cv::Mat bg = backdrop(kMargin);
  const Eigen::Vector2d at(110, 120);
  const cv::Point jump(60, 0);
  const auto acquired = [&](vision::ColourTracker& tracker) {
    const vision::MotionBlob m =
        vision::detect_motion(scene(bg, at, 0, {}, kMargin), scene(bg, at, 10, {}, kMargin));
    ASSERT_TRUE(m.found);
    ASSERT_TRUE(tracker.acquire(scene(bg, at, 10, {}, kMargin), m.mask));
    ASSERT_TRUE(tracker.track(scene(bg, at, 10, {}, kMargin)).tracked);
  };
  const Eigen::Vector2d moved = at + Eigen::Vector2d(jump.x, jump.y);
  const cv::Mat after = scene(bg, moved, 10, jump, kMargin);
  vision::ColourTracker shifted;
  acquired(shifted);
  shifted.shift_window(cv::Matx33d(1, 0, jump.x, 0, 1, jump.y, 0, 0, 1));
  const vision::ColourTrack t = shifted.track(after);
  ASSERT_TRUE(t.tracked);
  EXPECT_LT((t.centre_px - moved).norm(), 1.0);
  vision::ColourTracker unshifted;
  acquired(unshifted);
  EXPECT_FALSE(unshifted.track(after).tracked);
}
