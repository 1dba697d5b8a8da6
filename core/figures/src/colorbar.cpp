#include "colorbar.hpp"

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "axes.hpp"
#include "colormap_detail.hpp"

namespace somasim::figures::detail {

int colorbar_total_width(Range values, int bar_height, const std::string& label,
                         const Fonts& fonts) {
  const AxisTicks t = make_y_ticks(values, bar_height);
  int w = kColorbarGap + kColorbarWidth + kTickLen + 5 + max_label_width(t, fonts.tick());
  if (!label.empty()) w += kPad + label_height(fonts.label()) + 6;
  return w + kPad;
}

void draw_colorbar(cv::Mat& img, cv::Rect bar, Colormap map, Range values, const std::string& label,
                   const Fonts& fonts) {
  cv::Mat levels(bar.height, 1, CV_8UC1);
  for (int r = 0; r < bar.height; ++r)
    levels.at<std::uint8_t>(r) = quantise(1.0 - (r + 0.5) / bar.height);
  cv::Mat col = apply_colormap(levels, map);
  cv::Mat wide;
  cv::repeat(col, 1, bar.width, wide);
  wide.copyTo(img(bar));
  AxesFrame f{bar.x, bar.y, bar.width, bar.height, Range{0, 1}, values};
  const AxisTicks t = make_y_ticks(values, bar.height);
  const cv::Scalar black = bgr(kBlack);
  cv::rectangle(img, {bar.x - 1, bar.y - 1}, {bar.x + bar.width, bar.y + bar.height}, black, 1);
  const int right = bar.x + bar.width;
  int max_w = 0;
  for (std::size_t i = 0; i < t.values.size(); ++i) {
    const int y = std::clamp(static_cast<int>(std::floor(px(f, 0, t.values[i]).y)), bar.y - 1,
                             bar.y + bar.height);
    cv::line(img, {right, y}, {right + kTickLen, y}, black, 1);
    put_text(img, t.labels[i], {right + kTickLen + 5.0, y + 0.5}, HAlign::kLeft, VAlign::kMiddle,
             fonts.tick(), kBlack);
    max_w = std::max(max_w, text_size(t.labels[i], fonts.tick()).width);
  }
  if (!label.empty())
    put_text(img, label,
             {right + kTickLen + 5.0 + max_w + kPad + label_height(fonts.label()) / 2.0 + 3,
              bar.y + bar.height / 2.0},
             HAlign::kCenter, VAlign::kMiddle, fonts.label(), kBlack, 1, true);
}

}  // namespace somasim::figures::detail
