#include "somasim/diagnostics.hpp"

#include <algorithm>
#include <tuple>

#include "somasim/error.hpp"

namespace somasim {

std::string Diagnostic::str() const {
  std::string out = where.str() + ": ";
  if (!node.empty()) out += "node '" + node + "'" + (key.empty() ? ": " : ", ");
  if (!key.empty()) out += "key '" + key + "': ";
  return out + message;
}

void Diagnostics::add(SourceLocation where, std::string node, std::string key,
                      std::string message) {
  ++total_;
  if (items_.size() < kMaxKept)
    items_.push_back({std::move(where), std::move(node), std::move(key), std::move(message)});
}

void Diagnostics::throw_if_any() const {
  if (total_ == 0) return;
  if (total_ == 1) throw InputError(items_.front().str());
  // In file order: easier to read and to fix from top to bottom.
  std::vector<Diagnostic> sorted = items_;
  std::stable_sort(sorted.begin(), sorted.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::tie(a.where.line, a.where.column) < std::tie(b.where.line, b.where.column);
  });
  std::string msg = std::to_string(total_) + " errors:";
  for (std::size_t i = 0; i < sorted.size() && i < kMaxShown; ++i) msg += "\n  " + sorted[i].str();
  if (total_ > kMaxShown) msg += "\n  ... and " + std::to_string(total_ - kMaxShown) + " more";
  throw InputError(msg);
}

namespace {
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t subst = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, subst});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}
}  // namespace

std::string nearest_name(const std::string& name, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, name.size() / 3) + 1;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(name, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  if (best.empty() && name.size() >= 3)  // a truncated name: "rate" for "rate_hz"
    for (const auto& c : candidates)
      if (c.size() > name.size() && c.compare(0, name.size(), name) == 0) return c;
  return best;
}

std::string did_you_mean(const std::string& name, const std::vector<std::string>& candidates) {
  const std::string best = nearest_name(name, candidates);
  return best.empty() ? "" : " (did you mean '" + best + "'?)";
}

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace somasim
