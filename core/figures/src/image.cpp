// PNG input/output and the default palette.
#include <fstream>
#include <system_error>

#include <opencv2/imgcodecs.hpp>

#include "canvas.hpp"
#include "somasim/error.hpp"
#include "somasim/figures/figure.hpp"

namespace somasim::figures {

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
  // Fixed compression level: identical pixels give identical bytes.
  cv::imencode(".png", detail::to_mat(image), bytes, {cv::IMWRITE_PNG_COMPRESSION, 6});
  const auto parent = path.parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
    throw InputError("cannot write PNG file '" + path.string() + "': directory '" +
                     parent.string() + "' does not exist");
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError("cannot write PNG file '" + path.string() + "': cannot open it");
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw InputError("cannot write PNG file '" + path.string() + "': write failed");
}

Image load_png(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError("cannot read image '" + path.string() + "': no such file");
  cv::Mat m = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (m.empty())
    throw InputError("cannot read image '" + path.string() + "': not a decodable image");
  return detail::to_image(m);
}

}  // namespace somasim::figures
