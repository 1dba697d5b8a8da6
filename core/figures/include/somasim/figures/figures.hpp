#pragma once
/// @file
/// somasim_figures: publication-readable PNG plots (heatmaps, line plots, scatter plots,
/// composition). Umbrella header.
#include "somasim/figures/colormap.hpp"
#include "somasim/figures/compose.hpp"
#include "somasim/figures/figure.hpp"
#include "somasim/figures/heatmap.hpp"
#include "somasim/figures/image_grid.hpp"
#include "somasim/figures/line_plot.hpp"
#include "somasim/figures/scatter.hpp"
#include "somasim/figures/ticks.hpp"
