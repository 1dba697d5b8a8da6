// The video encoder that runs on its own thread: every frame handed over is in the file, in
// order; the same frames give the same bytes however the encoder is paced; a bounded queue; and
// errors (a wrong frame size, a file that cannot be written) reach the caller.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "../../../core/render/src/video_encoder.hpp"
#include "somasim/error.hpp"

using namespace somasim;
using namespace somasim::render;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "somasim-test-video-encoder";
  fs::create_directories(dir);
  const fs::path file = dir / name;
  fs::remove(file);
  return file;
}

// Frame k: a bright square moving across a dark 96 x 64 image, its colour changing with k.
cv::Mat frame(int k) {
  cv::Mat bgr(64, 96, CV_8UC3, cv::Scalar(20, 30, 40));
  cv::rectangle(bgr, cv::Rect(4 * k % 80, 10 + k % 30, 16, 16),
                cv::Scalar(255 - 5 * k % 200, 40 + 7 * k % 200, 200), cv::FILLED);
  return bgr;
}

std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

int frames_in(const fs::path& file) {
  cv::VideoCapture capture(file.string());
  int n = 0;
  for (cv::Mat f; capture.read(f);) ++n;
  return n;
}

}  // namespace

TEST(VideoEncoder, EveryFrameHandedOverIsInTheFile) {
  const fs::path file = scratch("all.mp4");
  {
    VideoEncoder encoder(file, 10.0, 2);
    for (int k = 0; k < 40; ++k) encoder.add(frame(k));
    encoder.close();
  }
  EXPECT_EQ(frames_in(file), 40);
  // The first frame decodes to (about) what was handed over: the square is where it was drawn.
  cv::VideoCapture capture(file.string());
  cv::Mat first;
  ASSERT_TRUE(capture.read(first));
  EXPECT_GT(first.at<cv::Vec3b>(18, 8)[2], 150);
  EXPECT_LT(first.at<cv::Vec3b>(50, 80)[2], 90);
}

TEST(VideoEncoder, TheSameFramesGiveTheSameBytesWhateverThePace) {
  const fs::path fast = scratch("fast.mp4"), slow = scratch("slow.mp4");
  {
    VideoEncoder encoder(fast, 10.0, 1);
    for (int k = 0; k < 25; ++k) encoder.add(frame(k));
  }  // the destructor encodes what was handed over
  {
    VideoEncoder encoder(slow, 10.0, 64);
    for (int k = 0; k < 25; ++k) {
      encoder.add(frame(k));
      if (k % 5 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    encoder.close();
  }
  const std::string a = bytes_of(fast), b = bytes_of(slow);
  EXPECT_GT(a.size(), 1000U);
  EXPECT_EQ(a, b);
}

TEST(VideoEncoder, TheCallerKeepsItsFrame) {
  const fs::path file = scratch("copy.mp4");
  VideoEncoder encoder(file, 10.0);
  cv::Mat f = frame(3);
  encoder.add(f);
  f.setTo(cv::Scalar(0, 0, 0));  // reused by the caller at once, as a port's image is
  encoder.add(frame(4));
  encoder.close();
  cv::VideoCapture capture(file.string());
  cv::Mat first;
  ASSERT_TRUE(capture.read(first));
  EXPECT_GT(first.at<cv::Vec3b>(21, 20)[2], 150);
}

TEST(VideoEncoder, AFrameOfAnotherSizeIsRefused) {
  const fs::path file = scratch("sizes.mp4");
  VideoEncoder encoder(file, 10.0);
  encoder.add(frame(0));
  try {
    encoder.add(cv::Mat(32, 32, CV_8UC3, cv::Scalar(0, 0, 0)));
    FAIL() << "no error";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("a frame is 32 x 32 px, the video 96 x 64"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(encoder.close());
  EXPECT_EQ(frames_in(file), 1);
}

TEST(VideoEncoder, AFileThatCannotBeWrittenIsAnErrorNamingIt) {
  const fs::path file = fs::temp_directory_path() / "somasim-no-such-folder" / "x" / "v.mp4";
  VideoEncoder encoder(file, 10.0, 1);
  std::string error;
  try {
    for (int k = 0; k < 10; ++k) encoder.add(frame(k));
    encoder.close();
  } catch (const RunError& e) {
    error = e.what();
  }
  EXPECT_NE(error.find("video '" + file.string() + "': cannot be written"), std::string::npos)
      << error;
  // Once failed, it stays failed.
  EXPECT_THROW(encoder.close(), RunError);
}
