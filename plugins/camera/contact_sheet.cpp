#include "contact_sheet.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "somasim/error.hpp"

namespace somasim::plugins {

void write_contact_sheet(const std::vector<SheetRow>& rows,
                         const std::vector<std::string>& camera_names,
                         const std::filesystem::path& file) {
  if (rows.empty() || rows.front().views.empty()) return;
  const int gap = 4, title = 22;
  const int w = rows.front().views.front().cols, h = rows.front().views.front().rows;
  const int cols = static_cast<int>(rows.front().views.size());
  cv::Mat sheet(title + static_cast<int>(rows.size()) * (h + gap), cols * (w + gap) + gap, CV_8UC3,
                cv::Scalar(255, 255, 255));
  for (int c = 0; c < cols && c < static_cast<int>(camera_names.size()); ++c)
    cv::putText(sheet, camera_names[c], {gap + c * (w + gap) + 4, 16}, cv::FONT_HERSHEY_SIMPLEX,
                0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const int y = title + static_cast<int>(r) * (h + gap);
    for (int c = 0; c < cols && c < static_cast<int>(rows[r].views.size()); ++c) {
      cv::Mat bgr;
      cv::cvtColor(rows[r].views[c], bgr, cv::COLOR_RGB2BGR);
      bgr.copyTo(sheet(cv::Rect(gap + c * (w + gap), y, w, h)));
    }
    cv::putText(sheet, fmt::format("t = {:.2f} s", rows[r].time_s), {gap + 4, y + 16},
                cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  }
  if (!cv::imwrite(file.string(), sheet))
    throw RunError(fmt::format("figure '{}': cannot be written", file.string()));
}

}  // namespace somasim::plugins
