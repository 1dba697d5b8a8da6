#pragma once
// The camera plugin's contact sheet: left/right RGB pairs side by side, one row per chosen
// time, each row labelled with its sim time.
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace somasim::plugins {

struct SheetRow {
  double time_s = 0.0;
  std::vector<cv::Mat> views;  ///< CV_8UC3 R G B, one per camera (same size)
};

/// Writes the rows as one figure, PNG and SVG (cameras as columns, times as rows, 4 px gaps).
/// InputError naming the file when it cannot be written.
void write_contact_sheet(const std::vector<SheetRow>& rows,
                         const std::vector<std::string>& camera_names,
                         const std::filesystem::path& file);

}  // namespace somasim::plugins
