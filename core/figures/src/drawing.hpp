#pragma once
// Private: the recorded vector drawing of a figure (a cairo recording surface).
#include <mutex>
#include <string>

#include <cairo.h>

#include "somasim/figures/figure.hpp"

namespace somasim::figures {

class Drawing {
 public:
  /// Takes ownership of `recording`, a finished recording surface of width x height px.
  Drawing(cairo_surface_t* recording, int width, int height);
  ~Drawing();
  Drawing(const Drawing&) = delete;
  Drawing& operator=(const Drawing&) = delete;

  cairo_surface_t* surface() const { return recording_; }
  /// Held while the recording is replayed (cairo attaches snapshots to a source surface while
  /// painting it, without a lock of its own): figures and their copies may be saved or composed
  /// from several threads.
  std::mutex& mutex() const { return mutex_; }
  int width() const { return width_; }
  int height() const { return height_; }

  /// The drawing's pixels, on white.
  Image rasterise() const;
  /// The drawing as an SVG document (deterministic bytes for identical drawings).
  std::string svg() const;

 private:
  cairo_surface_t* recording_ = nullptr;
  mutable std::mutex mutex_;
  int width_ = 0, height_ = 0;
};

}  // namespace somasim::figures
