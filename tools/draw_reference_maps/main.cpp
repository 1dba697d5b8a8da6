// draw_reference_maps: draws one of the authors' stored 8x4 (D, TTC) count tables from
// histograms_2D_long.csv as a smoothed activation landscape (PNG).
//
//   draw_reference_maps CSV SOURCE OUT.png [--part P] [--taxel N] [--title T]
//                       [--colormap viridis|jet|turbo|inferno] [--no-bin-grid]
//
// Drawn exactly like the pps_learner's landscapes (somasim::pps::landscape_heatmap): r =
// pos / (pos + neg) per bin, Parzen kernels at the bin centres with sigma = one bin width,
// normalised as the pps library does, with the Fig 8 regression line.
// Exit codes: 0 done, 2 bad arguments or input.
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "reference_map.hpp"
#include "somasim/error.hpp"
#include "somasim/figures/heatmap.hpp"
#include "somasim/pps/landscape_plot.hpp"

namespace {

constexpr const char* kUsage =
    "usage: draw_reference_maps CSV SOURCE OUT.png [--part P] [--taxel N] [--title T]\n"
    "                           [--colormap viridis|jet|turbo|inferno] [--no-bin-grid]\n"
    "  CSV     histograms_2D_long.csv (source,protocol_or_part,taxel,d_bin,ttc_bin,...)\n"
    "  SOURCE  value of the 'source' column, e.g. Fig2.mat\n";

using somasim::InputError;
namespace fig = somasim::figures;

fig::Colormap parse_colormap(const std::string& s) {
  if (s == "viridis") return fig::Colormap::kViridis;
  if (s == "jet") return fig::Colormap::kJet;
  if (s == "turbo") return fig::Colormap::kTurbo;
  if (s == "inferno") return fig::Colormap::kInferno;
  throw InputError("unknown colormap '" + s + "'; expected viridis, jet, turbo or inferno");
}

int run(const std::vector<std::string>& args) {
  std::vector<std::string> positional;
  somasim::tools::TableKey key;
  std::string title;
  bool bin_grid = true;
  fig::Colormap cmap = fig::Colormap::kViridis;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw InputError("option " + a + " needs a value");
      return args[++i];
    };
    if (a == "-h" || a == "--help") {
      std::cout << kUsage;
      return 0;
    } else if (a == "--part") {
      key.part = value();
    } else if (a == "--taxel") {
      const std::string& v = value();
      try {
        key.taxel = std::stoi(v);
      } catch (const std::exception&) {
        throw InputError("--taxel expects an integer, got '" + v + "'");
      }
    } else if (a == "--title") {
      title = value();
    } else if (a == "--colormap") {
      cmap = parse_colormap(value());
    } else if (a == "--no-bin-grid") {
      bin_grid = false;
    } else if (a.rfind("--", 0) == 0) {
      throw InputError("unknown option '" + a + "'");
    } else {
      positional.push_back(a);
    }
  }
  if (positional.size() != 3)
    throw InputError("expected CSV, SOURCE and OUT.png, got " + std::to_string(positional.size()) +
                     " arguments");
  key.source = positional[1];
  const auto table = somasim::tools::read_table(positional[0], key);

  // The same landscape as the pps_learner's figures: the paper's Parzen variant (kernels at
  // bin centres, sigma = one bin width) over the table's own grid.
  somasim::pps::GridSpec grid;
  grid.d_min = table.d_edges.front();
  grid.d_max = table.d_edges.back();
  grid.d_bins = table.d_bins;
  grid.ttc_min = table.ttc_edges.front();
  grid.ttc_max = table.ttc_edges.back();
  grid.ttc_bins = table.ttc_bins;
  std::vector<somasim::pps::TaxelMap::Count> pos(table.pos.begin(), table.pos.end());
  std::vector<somasim::pps::TaxelMap::Count> neg(table.neg.begin(), table.neg.end());
  const somasim::pps::TaxelMap map(grid, somasim::pps::ParzenSpec::paper(), pos, neg);
  somasim::pps::LandscapeOptions options;
  options.title = !title.empty()
                      ? title
                      : table.source + ": " + table.part + ", taxel " + std::to_string(table.taxel);
  options.bin_grid = bin_grid;
  fig::HeatmapSpec spec = somasim::pps::landscape_heatmap(map, options);
  spec.colormap = cmap;
  fig::save_figure(fig::render_heatmap(spec), positional[2]);
  std::cout << "wrote " << positional[2] << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    if (argc < 2) std::cerr << kUsage;
    return 2;
  }
}
