#include "drawing.hpp"

#include <algorithm>
#include <cctype>
#include <map>

#include <cairo-svg.h>

#include "somasim/error.hpp"

namespace somasim::figures {

Drawing::Drawing(cairo_surface_t* recording, int width, int height)
    : recording_(recording), width_(width), height_(height) {}

Drawing::~Drawing() {
  cairo_surface_destroy(recording_);
}

Image Drawing::rasterise() const {
  const std::lock_guard lock(mutex_);
  cairo_surface_t* target = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_, height_);
  cairo_t* cr = cairo_create(target);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_source_surface(cr, recording_, 0, 0);
  cairo_paint(cr);
  cairo_destroy(cr);
  cairo_surface_flush(target);
  if (const cairo_status_t status = cairo_surface_status(target); status != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(target);
    throw RunError(std::string("figure: drawing failed: ") + cairo_status_to_string(status));
  }
  Image out;
  out.width = width_;
  out.height = height_;
  out.rgb.resize(static_cast<std::size_t>(width_) * height_ * 3);
  const unsigned char* data = cairo_image_surface_get_data(target);
  const int stride = cairo_image_surface_get_stride(target);
  for (int r = 0; r < height_; ++r) {
    const auto* row =
        reinterpret_cast<const std::uint32_t*>(data + static_cast<std::ptrdiff_t>(r) * stride);
    for (int c = 0; c < width_; ++c) {
      const std::size_t i = 3 * (static_cast<std::size_t>(r) * width_ + c);
      out.rgb[i] = static_cast<std::uint8_t>(row[c] >> 16);
      out.rgb[i + 1] = static_cast<std::uint8_t>(row[c] >> 8);
      out.rgb[i + 2] = static_cast<std::uint8_t>(row[c]);
    }
  }
  cairo_surface_destroy(target);
  return out;
}

namespace {
cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

/// Cairo names an SVG's surfaces and images after process-wide counters ("surface225"), which
/// depend on what was drawn before. Renumbers them in order of appearance, so the document
/// depends on the drawing only.
std::string renumber_ids(const std::string& svg) {
  std::string out;
  out.reserve(svg.size());
  std::map<std::string, std::string> renamed;
  std::map<std::string, int> next;
  std::size_t pos = 0;
  while (pos < svg.size()) {
    const std::size_t id = svg.find("id=\"", pos), href = svg.find("href=\"#", pos);
    const std::size_t at = std::min(id, href);
    if (at == std::string::npos) break;
    const std::size_t name = at + (at == id ? 4 : 7);
    out.append(svg, pos, name - pos);
    pos = name;
    for (const char* kind : {"surface", "image"}) {
      const std::size_t len = std::char_traits<char>::length(kind);
      if (svg.compare(name, len, kind) != 0) continue;
      std::size_t end = name + len;
      while (end < svg.size() && std::isdigit(static_cast<unsigned char>(svg[end]))) ++end;
      if (end == name + len || end >= svg.size() || svg[end] != '"') break;
      const std::string old = svg.substr(name, end - name);
      auto [it, inserted] = renamed.try_emplace(old);
      if (inserted) it->second = kind + std::to_string(next[kind]++);
      out += it->second;
      pos = end;
      break;
    }
  }
  out.append(svg, pos, std::string::npos);
  return out;
}
}  // namespace

std::string Drawing::svg() const {
  const std::lock_guard lock(mutex_);
  std::string out;
  cairo_surface_t* target = cairo_svg_surface_create_for_stream(append, &out, width_, height_);
  cairo_svg_surface_restrict_to_version(target, CAIRO_SVG_VERSION_1_1);
  cairo_svg_surface_set_document_unit(target, CAIRO_SVG_UNIT_PX);
  cairo_t* cr = cairo_create(target);
  cairo_set_source_surface(cr, recording_, 0, 0);
  cairo_paint(cr);
  cairo_destroy(cr);
  cairo_surface_finish(target);
  const cairo_status_t status = cairo_surface_status(target);
  cairo_surface_destroy(target);
  if (status != CAIRO_STATUS_SUCCESS)
    throw RunError(std::string("figure: SVG output failed: ") + cairo_status_to_string(status));
  return renumber_ids(out);
}

}  // namespace somasim::figures
