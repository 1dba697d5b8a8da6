#include "somasim/sweep/hash.hpp"

#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace somasim::sweep {

std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::string content_hash(std::string_view bytes) {
  return fmt::format("fnv1a64:{:016x}", fnv1a64(bytes));
}

std::optional<std::string> file_hash(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream s;
  s << in.rdbuf();
  return content_hash(s.str());
}

}  // namespace somasim::sweep
