#include "somasim/pps/ini_export.hpp"

#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "somasim/atomic_file.hpp"
#include "somasim/error.hpp"

namespace somasim::pps {

namespace {

void write_counts(std::ostream& out, const std::vector<TaxelMap::Count>& counts) {
  out << '(';
  for (std::size_t i = 0; i < counts.size(); ++i) out << (i ? " " : "") << counts[i];
  out << ')';
}

}  // namespace

void write_taxels2d_ini(const std::vector<LearnedState>& parts, std::ostream& out) {
  for (const LearnedState& s : parts) {
    if (s.model != PpsModel::kDTtc)
      throw InputError("body part \"" + s.body_part + "\" has a " + to_string(s.model) +
                       " map; the .ini format holds (D, TTC) maps only (save it as .json)");
    const GridSpec& g = s.grid;
    out << '[' << s.body_part << "]\n"
        << "modality 2D\n"
        << "nTaxels " << s.taxels.size() << '\n'
        << fmt::format("ext ({} {} {} {})\n", g.d_min, g.d_max, g.ttc_min, g.ttc_max) << "binsNum ("
        << g.d_bins << ' ' << g.ttc_bins << ")\n";
    for (const LearnedTaxel& t : s.taxels) {
      out << t.id << ' ';
      write_counts(out, t.pos);
      out << ' ';
      write_counts(out, t.neg);
      out << '\n';
    }
  }
}

void save_taxels2d_ini(const std::vector<LearnedState>& parts, const std::string& path) {
  std::ostringstream out;
  write_taxels2d_ini(parts, out);
  try {
    write_file_atomically(path, out.str());
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
}

bool is_ini_learned_file(const std::string& path) {
  return std::filesystem::path(path).extension() == ".ini";
}

}  // namespace somasim::pps
