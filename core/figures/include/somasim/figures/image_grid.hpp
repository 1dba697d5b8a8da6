#pragma once
/// @file
/// A grid of images (e.g. camera frames: cameras as columns, times as rows) with column titles
/// and a label on each row.
#include <string>
#include <vector>

#include "somasim/figures/figure.hpp"

namespace somasim::figures {

struct ImageGridSpec {
  std::string title;                       ///< above everything; empty: none
  std::vector<std::string> column_titles;  ///< above the columns (may be fewer than columns)
  std::vector<std::string> row_labels;     ///< on each row's first image, top left (or empty)
  std::vector<std::vector<Image>> rows;    ///< every image the same size
  int gap_px = 4;                          ///< between images and around the grid [px]
  double font_scale = 1.0;
};

/// Renders the grid (no axes: Figure::axes is empty); the images keep their pixels. Throws
/// somasim::InputError when there are no images, an image is empty or the sizes differ.
Figure render_image_grid(const ImageGridSpec& spec);

}  // namespace somasim::figures
