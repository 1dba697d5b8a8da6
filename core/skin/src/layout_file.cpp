#include "somasim/skin/layout_file.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "somasim/atomic_file.hpp"
#include "somasim/error.hpp"
#include "somasim/skin/icub_positions_file.hpp"

namespace somasim::skin {
namespace {

constexpr const char* kColumns[] = {"id", "x", "y", "z", "nx", "ny", "nz", "module"};

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string current;
  for (char c : line) {
    if (c == '#') break;
    if (c == ' ' || c == '\t' || c == ',' || c == '\r') {
      if (!current.empty()) fields.push_back(std::move(current));
      current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) fields.push_back(std::move(current));
  return fields;
}

}  // namespace

SkinLayout load_layout_file(const std::filesystem::path& file, const std::string& body_part,
                            int link) {
  if (is_icub_positions_file(file)) return load_icub_positions_file(file, body_part, link);
  const std::string name = file.string();
  std::ifstream in(file);
  if (!in)
    throw InputError(name + ": cannot open the skin layout file (" +
                     (std::filesystem::exists(file) ? "not readable" : "no such file") + ")");
  SkinLayout layout;
  layout.body_part = body_part;
  layout.link = link;
  std::vector<int> modules;
  std::map<int, int> line_of_id;
  std::size_t columns = 0;
  int columns_line = 0;
  std::string text;
  for (int line_no = 1; std::getline(in, text); ++line_no) {
    const std::vector<std::string> f = split_fields(text);
    if (f.empty()) continue;
    const std::string where = fmt::format("{}:{}: ", name, line_no);
    if (f.size() != 7 && f.size() != 8)
      throw InputError(where + fmt::format("expected 7 or 8 fields (id x y z nx ny nz [module]), "
                                           "got {}",
                                           f.size()));
    if (columns == 0) {
      columns = f.size();
      columns_line = line_no;
    } else if (f.size() != columns) {
      throw InputError(where + fmt::format("expected {} fields like line {}, got {}", columns,
                                           columns_line, f.size()));
    }
    const auto integer = [&](std::size_t k) {
      int v = 0;
      const auto [end, ec] = std::from_chars(f[k].data(), f[k].data() + f[k].size(), v);
      if (ec != std::errc() || end != f[k].data() + f[k].size() || v < 0)
        throw InputError(where + fmt::format("{} '{}' is not an integer >= 0", kColumns[k], f[k]));
      return v;
    };
    double v[6];
    for (std::size_t k = 1; k <= 6; ++k) {
      std::size_t used = 0;
      bool ok = true;
      try {
        v[k - 1] = std::stod(f[k], &used);
      } catch (const std::exception&) {
        ok = false;
      }
      if (!ok || used != f[k].size() || !std::isfinite(v[k - 1]))
        throw InputError(where + fmt::format("{} '{}' is not a finite number", kColumns[k], f[k]));
    }
    const int id = integer(0);
    if (const auto it = line_of_id.find(id); it != line_of_id.end())
      throw InputError(where + fmt::format("taxel id {} already used on line {}", id, it->second));
    line_of_id[id] = line_no;
    const Eigen::Vector3d normal(v[3], v[4], v[5]);
    if (normal.norm() < 1e-9)
      throw InputError(where + fmt::format("the normal of taxel {} is zero; expected an outward "
                                           "direction",
                                           id));
    layout.ids.push_back(id);
    layout.positions.emplace_back(v[0], v[1], v[2]);
    layout.normals.push_back(normal.normalized());
    if (columns == 8) modules.push_back(integer(7));
  }
  if (layout.ids.empty())
    throw InputError(name + ": no taxels; expected lines 'id x y z nx ny nz [module]'");
  if (columns == 8)
    group_by_key(layout, modules);
  else
    one_module_per_taxel(layout);
  return layout;
}

void save_layout_file(const SkinLayout& layout, const std::filesystem::path& file) {
  std::ostringstream out;
  out << "# skin layout of '" << layout.body_part
      << "' (link frame): id x y z [m] nx ny nz module\n";
  for (std::size_t i = 0; i < layout.size(); ++i) {
    const auto& p = layout.positions[i];
    const auto& n = layout.normals[i];
    out << fmt::format("{} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {}\n", layout.ids[i], p.x(),
                       p.y(), p.z(), n.x(), n.y(), n.z(),
                       layout.virtual_taxels[static_cast<std::size_t>(layout.module[i])].id);
  }
  try {
    write_file_atomically(file, out.str());
  } catch (const std::runtime_error& e) {
    throw InputError(std::string(e.what()) + " (the skin layout file)");
  }
}

}  // namespace somasim::skin
