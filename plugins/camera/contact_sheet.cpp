#include "contact_sheet.hpp"

#include <algorithm>
#include <cstdint>

#include <fmt/format.h>

#include "somasim/figures/image_grid.hpp"

namespace somasim::plugins {

namespace {
figures::Image to_image(const cv::Mat& rgb) {
  figures::Image out{rgb.cols, rgb.rows, {}};
  out.rgb.resize(static_cast<std::size_t>(rgb.cols) * rgb.rows * 3);
  for (int y = 0; y < rgb.rows; ++y)
    std::copy_n(rgb.ptr<std::uint8_t>(y), static_cast<std::size_t>(rgb.cols) * 3,
                out.rgb.begin() + static_cast<std::ptrdiff_t>(y) * rgb.cols * 3);
  return out;
}
}  // namespace

void write_contact_sheet(const std::vector<SheetRow>& rows,
                         const std::vector<std::string>& camera_names,
                         const std::filesystem::path& file) {
  if (rows.empty() || rows.front().views.empty()) return;
  figures::ImageGridSpec spec;
  spec.column_titles = camera_names;
  for (const SheetRow& row : rows) {
    spec.row_labels.push_back(fmt::format("t = {:.2f} s", row.time_s));
    std::vector<figures::Image> images;
    for (const cv::Mat& view : row.views) images.push_back(to_image(view));
    spec.rows.push_back(std::move(images));
  }
  figures::save_figure(figures::render_image_grid(spec), file);
}

}  // namespace somasim::plugins
