#include "skin_figure.hpp"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

#include "somasim/figures/compose.hpp"
#include "somasim/figures/scatter.hpp"

namespace somasim::plugins {

figures::Figure render_skin_layout(const std::vector<SkinFigurePanel>& panels) {
  std::vector<figures::Figure> rendered;
  for (const auto& p : panels) {
    const skin::SkinLayout& layout = *p.layout;
    const auto uv = skin::surface_coordinates(*p.patch, layout.positions);
    figures::ScatterGroup all;
    all.label = "taxels";
    all.color = figures::Color{170, 170, 170};
    all.size_px = 4;
    figures::ScatterGroup centres;
    centres.label = "virtual taxels";
    centres.color = figures::Color{0, 0, 0};
    centres.marker = figures::Marker::kCross;
    figures::ScatterGroup fired;
    fired.label = "fired";
    fired.color = figures::Color{214, 39, 40};
    fired.size_px = 6;
    figures::ScatterGroup touched;
    touched.label = "touched virtual";
    touched.color = figures::Color{214, 39, 40};
    touched.marker = figures::Marker::kDiamond;
    touched.size_px = 12;
    for (std::size_t i = 0; i < uv.size(); ++i) {
      auto& g = p.fired[i] ? fired : all;
      g.x.push_back(uv[i].x());
      g.y.push_back(uv[i].y());
    }
    for (const auto& v : layout.virtual_taxels) {
      const auto& c = uv[static_cast<std::size_t>(v.centre)];
      auto& g = p.touched.count(v.id) ? touched : centres;
      g.x.push_back(c.x());
      g.y.push_back(c.y());
    }
    figures::ScatterSpec spec;
    std::string part = layout.body_part;
    std::replace(part.begin(), part.end(), '_', ' ');
    if (!part.empty())
      part[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(part[0])));
    spec.title = fmt::format("{}: {} taxels in {} virtual taxels, {} contact events", part,
                             layout.size(), layout.virtual_taxels.size(), p.events);
    std::tie(spec.x_label, spec.y_label) = skin::surface_axis_labels(*p.patch);
    for (auto* g : {&all, &fired, &centres, &touched})
      if (!g->x.empty()) spec.groups.push_back(std::move(*g));
    spec.equal_aspect = true;
    spec.legend = figures::LegendPosition::kBest;
    spec.width = 700;
    spec.height = 600;
    rendered.push_back(figures::render_scatter(spec));
  }
  return figures::compose_row(
      rendered, 10, "Skin layout: each patch unrolled onto its surface, in its link's frame");
}

}  // namespace somasim::plugins
