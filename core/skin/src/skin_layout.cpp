#include "somasim/skin/skin_layout.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <fmt/format.h>

#include "somasim/error.hpp"
#include "somasim/numeric.hpp"
#include "somasim/units.hpp"

namespace somasim::skin {
namespace {

constexpr double kDeg = kRadPerDeg;

double patch_param(const robot::SkinPatch& patch, const std::string& key) {
  const auto it = patch.params.find(key);
  if (it == patch.params.end())
    throw InputError("skin patch '" + patch.body_part + "': missing parameter '" + key + "'");
  return it->second;
}

double patch_param_or(const robot::SkinPatch& patch, const std::string& key, double fallback) {
  const auto it = patch.params.find(key);
  return it == patch.params.end() ? fallback : it->second;
}

constexpr double kMaxTaxels = 5e6;  // per patch

// Number of grid points exactly `spacing` apart that fit in `extent` (at least 1; counts above
// kMaxTaxels are held at kMaxTaxels + 1, which the patch's taxel count refuses).
int points_along(double extent, double spacing) {
  return 1 + to_integer_clamped<int>(extent / spacing + 1e-9, 0, static_cast<int>(kMaxTaxels),
                                     Rounding::kDown);
}

// Offset of point i of n, `spacing` apart, centred on 0.
double centred(int i, int n, double spacing) {
  return (i - 0.5 * (n - 1)) * spacing;
}

// Modules as near-equal rectangular blocks of an n_around × n_along grid (taxel index =
// row * n_around + column, row along the length).
void group_grid(SkinLayout& layout, int n_around, int n_along, int group_size) {
  const int g = std::max(1, group_size);
  const int m_around =
      std::clamp(static_cast<int>(std::lround(n_around / std::sqrt(double(g)))), 1, n_around);
  const int m_along =
      std::clamp(static_cast<int>(std::lround(double(n_around) * n_along / (double(g) * m_around))),
                 1, n_along);
  std::vector<int> keys(layout.size());
  for (int row = 0; row < n_along; ++row)
    for (int col = 0; col < n_around; ++col) {
      const int block_row = row * m_along / n_along;
      const int block_col = col * m_around / n_around;
      keys[static_cast<std::size_t>(row * n_around + col)] = block_row * m_around + block_col;
    }
  group_by_key(layout, keys);
}

}  // namespace

SkinLayout generate_layout(const robot::SkinPatch& patch, const LayoutOptions& options) {
  const std::string who = "skin patch '" + patch.body_part + "'";
  const double spacing = options.spacing > 0 ? options.spacing : patch_param(patch, "spacing");
  const double group_value = options.group_size > 0 ? static_cast<double>(options.group_size)
                                                    : patch_param_or(patch, "group_size", 1.0);
  const int group_size = to_integer<int>(group_value).value_or(0);
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw InputError(fmt::format("{}: spacing {} m; expected a spacing > 0 [m]", who, spacing));
  if (group_size < 1)
    throw InputError(fmt::format("{}: group_size {}; expected an integer >= 1", who, group_value));

  SkinLayout layout;
  layout.body_part = patch.body_part;
  layout.link = patch.link;
  const Eigen::Matrix3d rot = patch.origin.linear();
  int n_around = 0, n_along = 0;
  const auto reserve = [&] {
    const double n = double(n_around) * n_along;
    if (n > kMaxTaxels) {
      const bool counted = n_around <= kMaxTaxels && n_along <= kMaxTaxels;  // not held
      throw InputError(fmt::format("{}: spacing {} m gives {} taxels; expected at most 5e6", who,
                                   spacing, counted ? fmt::format("{}", n) : "more than 5e6"));
    }
    layout.positions.reserve(static_cast<std::size_t>(n));
    layout.normals.reserve(static_cast<std::size_t>(n));
  };

  if (patch.surface == "cylinder") {
    const double r = patch_param(patch, "radius");
    const double z0 = patch_param(patch, "z_min"), z1 = patch_param(patch, "z_max");
    const double a0 = patch_param_or(patch, "angle_min_deg", -180.0) * kDeg;
    const double a1 = patch_param_or(patch, "angle_max_deg", 180.0) * kDeg;
    if (!(r > 0) || !(z1 > z0) || !(a1 > a0) || a1 - a0 > 2 * std::numbers::pi + 1e-9)
      throw InputError(who +
                       ": expected radius > 0, z_min < z_max and an angle range of at most "
                       "one turn");
    const double arc = r * (a1 - a0);
    const bool full_turn = a1 - a0 > 2 * std::numbers::pi - 1e-9;
    // A full turn closes on itself: n columns spaced 2πr / n >= spacing apart.
    n_around = full_turn ? std::max(1, points_along(arc, spacing) - 1) : points_along(arc, spacing);
    const double step = full_turn ? (a1 - a0) / n_around : spacing / r;
    n_along = points_along(z1 - z0, spacing);
    reserve();
    const double a_mid = 0.5 * (a0 + a1), z_mid = 0.5 * (z0 + z1);
    for (int row = 0; row < n_along; ++row) {
      const double z = z_mid + centred(row, n_along, spacing);
      for (int col = 0; col < n_around; ++col) {
        const double a = full_turn ? a0 + (col + 0.5) * step : a_mid + centred(col, n_around, step);
        const Eigen::Vector3d n(std::cos(a), std::sin(a), 0.0);
        layout.positions.push_back(patch.origin * Eigen::Vector3d(r * n.x(), r * n.y(), z));
        layout.normals.push_back(rot * n);
      }
    }
  } else if (patch.surface == "box_face") {
    const double sx = patch_param(patch, "size_x"), sy = patch_param(patch, "size_y");
    if (!(sx > 0) || !(sy > 0)) throw InputError(who + ": expected size_x > 0 and size_y > 0");
    n_around = points_along(sx, spacing);
    n_along = points_along(sy, spacing);
    reserve();
    const Eigen::Vector3d normal = rot.col(2);
    for (int row = 0; row < n_along; ++row)
      for (int col = 0; col < n_around; ++col) {
        layout.positions.push_back(patch.origin * Eigen::Vector3d(centred(col, n_around, spacing),
                                                                  centred(row, n_along, spacing),
                                                                  0.0));
        layout.normals.push_back(normal);
      }
  } else {
    throw InputError(who + ": unknown surface '" + patch.surface +
                     "'; expected one of: cylinder, box_face");
  }
  layout.ids.resize(layout.positions.size());
  for (std::size_t i = 0; i < layout.ids.size(); ++i) layout.ids[i] = static_cast<int>(i);
  group_grid(layout, n_around, n_along, group_size);
  return layout;
}

std::vector<Eigen::Vector2d> surface_coordinates(const robot::SkinPatch& patch,
                                                 const std::vector<Eigen::Vector3d>& positions) {
  std::vector<Eigen::Vector2d> uv;
  uv.reserve(positions.size());
  const Eigen::Isometry3d to_surface = patch.origin.inverse();
  if (patch.surface == "cylinder") {
    const double r = patch_param(patch, "radius");
    const double a0 = patch_param_or(patch, "angle_min_deg", -180.0) * kDeg;
    for (const auto& p : positions) {
      const Eigen::Vector3d s = to_surface * p;
      // Angles in [a0, a0 + 2π) so that the patch is unrolled without a seam inside it.
      double a = std::atan2(s.y(), s.x());
      a = a0 + std::fmod(std::fmod(a - a0, 2 * std::numbers::pi) + 2 * std::numbers::pi,
                         2 * std::numbers::pi);
      uv.emplace_back(r * a, s.z());
    }
  } else {
    for (const auto& p : positions) {
      const Eigen::Vector3d s = to_surface * p;
      uv.emplace_back(s.x(), s.y());
    }
  }
  return uv;
}

std::pair<std::string, std::string> surface_axis_labels(const robot::SkinPatch& patch) {
  if (patch.surface == "cylinder") return {"around the axis, r * angle [m]", "along the axis [m]"};
  return {"face x [m]", "face y [m]"};
}

void one_module_per_taxel(SkinLayout& layout) {
  layout.module.resize(layout.size());
  layout.virtual_taxels.clear();
  layout.virtual_taxels.reserve(layout.size());
  for (std::size_t i = 0; i < layout.size(); ++i) {
    layout.module[i] = static_cast<int>(i);
    layout.virtual_taxels.push_back({layout.ids[i], static_cast<int>(i), {static_cast<int>(i)}});
  }
}

void group_by_key(SkinLayout& layout, const std::vector<int>& keys) {
  SOMASIM_CHECK(keys.size() == layout.size(), "one module key per taxel");
  std::map<int, std::vector<int>> members;
  for (std::size_t i = 0; i < keys.size(); ++i) members[keys[i]].push_back(static_cast<int>(i));
  layout.virtual_taxels.clear();
  layout.virtual_taxels.reserve(members.size());
  layout.module.assign(layout.size(), -1);
  for (auto& [key, idx] : members) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int i : idx) mean += layout.positions[static_cast<std::size_t>(i)];
    mean /= static_cast<double>(idx.size());
    int centre = idx.front();
    double best = std::numeric_limits<double>::infinity();
    for (int i : idx) {
      const double d = (layout.positions[static_cast<std::size_t>(i)] - mean).squaredNorm();
      if (d < best - 1e-15) {
        best = d;
        centre = i;
      }
    }
    const int v = static_cast<int>(layout.virtual_taxels.size());
    for (int i : idx) layout.module[static_cast<std::size_t>(i)] = v;
    layout.virtual_taxels.push_back({key, centre, std::move(idx)});
  }
}

}  // namespace somasim::skin
