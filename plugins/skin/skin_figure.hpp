#pragma once
// The skin layout figure: each part's taxels on its unrolled surface, fired taxels highlighted.
#include <set>
#include <vector>

#include "somasim/figures/figure.hpp"
#include "somasim/robot/robot_model.hpp"
#include "somasim/skin/skin_layout.hpp"

namespace somasim::plugins {

struct SkinFigurePanel {
  const robot::SkinPatch* patch = nullptr;
  const skin::SkinLayout* layout = nullptr;
  std::vector<bool> fired;  ///< per physical taxel: over threshold during an episode
  std::set<int> touched;    ///< virtual ids named in contact events
  std::size_t events = 0;
};

/// One scatter panel per part (left to right): physical taxels (grey), virtual taxel centres
/// (black crosses), fired taxels (red) and touched virtual taxels (red diamonds).
figures::Figure render_skin_layout(const std::vector<SkinFigurePanel>& panels);

}  // namespace somasim::plugins
