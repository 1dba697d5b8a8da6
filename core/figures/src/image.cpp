// PNG and SVG output, PNG input and the default palette.
#include <exception>
#include <fstream>
#include <string_view>
#include <system_error>
#include <thread>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "drawing.hpp"
#include "somasim/error.hpp"
#include "somasim/figures/figure.hpp"

namespace somasim::figures {
namespace {

cv::Mat to_bgr_mat(const Image& image) {
  cv::Mat m(image.height, image.width, CV_8UC3);
  for (int y = 0; y < image.height; ++y) {
    auto* p = m.ptr<cv::Vec3b>(y);
    for (int x = 0; x < image.width; ++x) {
      const Color c = image.at(x, y);
      p[x] = cv::Vec3b(c.b, c.g, c.r);
    }
  }
  return m;
}

/// Writes `bytes` to `path` through a temporary file renamed into place: a reader never sees a
/// file cut in half.
void write_whole_file(const std::filesystem::path& path, std::string_view bytes, const char* kind) {
  const std::string what = std::string("cannot write ") + kind + " file '" + path.string() + "': ";
  const auto parent = path.parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
    throw InputError(what + "directory '" + parent.string() + "' does not exist");
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(what + "cannot open it");
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      std::filesystem::remove(tmp, ec);
      throw InputError(what + "write failed");
    }
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(what + "cannot move it into place");
  }
}

}  // namespace

const std::vector<Color>& palette() {
  static const std::vector<Color> kTab10 = {
      {31, 119, 180}, {255, 127, 14},  {44, 160, 44},   {214, 39, 40},  {148, 103, 189},
      {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207}};
  return kTab10;
}

void save_png(const Image& image, const std::filesystem::path& path) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3)
    throw InputError("cannot write PNG file '" + path.string() + "': the image is empty or its " +
                     "pixel buffer does not match its size");
  std::vector<std::uint8_t> bytes;
  // Fixed compression level: identical pixels give identical bytes. Level 1, zlib's fastest:
  // figures of flat colours and text come out about a fifth larger than at level 6.
  cv::imencode(".png", to_bgr_mat(image), bytes, {cv::IMWRITE_PNG_COMPRESSION, 1});
  write_whole_file(path, {reinterpret_cast<const char*>(bytes.data()), bytes.size()}, "PNG");
}

void save_svg(const Figure& figure, const std::filesystem::path& path) {
  if (!figure.drawing)
    throw InputError("cannot write SVG file '" + path.string() +
                     "': the figure has pixels only (no vector drawing)");
  write_whole_file(path, figure.drawing->svg(), "SVG");
}

void save_figure(const Figure& figure, const std::filesystem::path& png_path) {
  if (!figure.drawing) {
    save_png(figure.image, png_path);
    return;
  }
  std::filesystem::path svg = png_path;
  svg.replace_extension(".svg");
  // The PNG is encoded on a thread of its own while this one writes the SVG (both are
  // compression-bound); the PNG's error, if any, is reported first, as if written first.
  std::exception_ptr png_error;
  std::thread png_writer([&] {
    try {
      save_png(figure.image, png_path);
    } catch (...) {
      png_error = std::current_exception();
    }
  });
  std::exception_ptr svg_error;
  try {
    save_svg(figure, svg);
  } catch (...) {
    svg_error = std::current_exception();
  }
  png_writer.join();
  if (png_error) std::rethrow_exception(png_error);
  if (svg_error) std::rethrow_exception(svg_error);
}

Image load_png(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError("cannot read image '" + path.string() + "': no such file");
  cv::Mat m = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (m.empty())
    throw InputError("cannot read image '" + path.string() + "': not a decodable image");
  Image out;
  out.width = m.cols;
  out.height = m.rows;
  out.rgb.resize(static_cast<std::size_t>(m.cols) * m.rows * 3);
  for (int y = 0; y < m.rows; ++y) {
    const auto* p = m.ptr<cv::Vec3b>(y);
    for (int x = 0; x < m.cols; ++x) {
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * m.cols + x);
      out.rgb[i] = p[x][2];
      out.rgb[i + 1] = p[x][1];
      out.rgb[i + 2] = p[x][0];
    }
  }
  return out;
}

}  // namespace somasim::figures
