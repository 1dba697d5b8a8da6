#include "somasim/pps/taxel_map.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "somasim/error.hpp"

namespace somasim::pps {

namespace {

// Gaussian weights exp(-(u - i)^2 / (2 s^2)) for i = 0..n-1, u in bin widths, by a recurrence
// started at the nearest anchor (3 exp() calls; decays to 0 without overflow).
inline void gauss_row(double u, double inv2s2, double q, int n, double* out) {
  int k = static_cast<int>(std::lround(u));
  k = std::clamp(k, 0, n - 1);
  const double du = u - k;
  double g = std::exp(-du * du * inv2s2);
  out[k] = g;
  double rho = std::exp((2.0 * du - 1.0) * inv2s2);  // g_{i+1} / g_i at i = k
  double gi = g;
  for (int i = k + 1; i < n; ++i) {
    gi *= rho;
    rho *= q;
    out[i] = gi;
  }
  rho = std::exp((-2.0 * du - 1.0) * inv2s2);  // g_{i-1} / g_i at i = k
  gi = g;
  for (int i = k - 1; i >= 0; --i) {
    gi *= rho;
    rho *= q;
    out[i] = gi;
  }
}

}  // namespace

TaxelMap::TaxelMap(const GridSpec& grid, const ParzenSpec& parzen)
    : TaxelMap(grid, parzen, std::vector<Count>(grid.size(), 0),
               std::vector<Count>(grid.size(), 0)) {}

TaxelMap::TaxelMap(const GridSpec& grid, const ParzenSpec& parzen, std::vector<Count> pos,
                   std::vector<Count> neg)
    : grid_(grid), parzen_(parzen), pos_(std::move(pos)), neg_(std::move(neg)) {
  SOMASIM_CHECK(grid_.validate().empty(), "invalid GridSpec");
  SOMASIM_CHECK(parzen_.validate().empty(), "invalid ParzenSpec");
  SOMASIM_CHECK(pos_.size() == grid_.size() && neg_.size() == grid_.size(),
                "count arrays must have grid.size() entries");
  const double shift = parzen_.anchor == KernelAnchor::kCentre ? 0.5 : 0.0;
  a0_ = grid_.d_min + shift * grid_.d_width();
  b0_ = grid_.ttc_min + shift * grid_.ttc_width();
  const double s = parzen_.sigma_scale;
  inv_sd_ = 1.0 / (2.0 * s * s);  // same in both axes: sigma is in bin widths
  inv_st_ = inv_sd_;
  qd_ = std::exp(-1.0 / (s * s));
  qt_ = qd_;
  ratio_.assign(grid_.size(), 0.0);
  refresh();
}

bool TaxelMap::add_sample(double d, double ttc, bool positive, bool refresh_now) {
  int i = 0, j = 0;
  if (!grid_.bin_of(d, ttc, i, j)) return false;
  add_to_bin(grid_.index(i, j), positive);
  if (refresh_now) refresh();
  return true;
}

double TaxelMap::ratio(int d_bin, int ttc_bin) const {
  return ratio_[static_cast<std::size_t>(grid_.index(d_bin, ttc_bin))];
}

void TaxelMap::kernel_d(double d, double* g) const {
  gauss_row((d - a0_) / grid_.d_width(), inv_sd_, qd_, grid_.d_bins, g);
}

void TaxelMap::kernel_t(double t, double* h) const {
  gauss_row((t - b0_) / grid_.ttc_width(), inv_st_, qt_, grid_.ttc_bins, h);
}

void TaxelMap::refresh() {
  const std::size_t n = grid_.size();
  for (std::size_t k = 0; k < n; ++k) {
    const double tot = static_cast<double>(pos_[k]) + static_cast<double>(neg_[k]);
    ratio_[k] = tot > 0.0 ? pos_[k] / tot : 0.0;
  }
  // Normaliser: max of f over the kernel anchors. With separable kernels the values at all
  // anchors are KD^T R KT, KD/KT being the Gaussian weights between anchors.
  const int nd = grid_.d_bins, nt = grid_.ttc_bins;
  std::array<double, kMaxBinsPerAxis> g{}, h{};
  std::array<double, kMaxBinsPerAxis * kMaxBinsPerAxis> kt{};  // kt[j * nt + l]
  for (int l = 0; l < nt; ++l) {
    gauss_row(static_cast<double>(l), inv_st_, qt_, nt, h.data());
    for (int j = 0; j < nt; ++j) kt[static_cast<std::size_t>(j * nt + l)] = h[j];
  }
  // rk[i * nt + l] = sum_j R_ij KT_jl
  std::array<double, kMaxBinsPerAxis * kMaxBinsPerAxis> rk{};
  for (int i = 0; i < nd; ++i)
    for (int l = 0; l < nt; ++l) {
      double s = 0.0;
      for (int j = 0; j < nt; ++j) s += ratio_[i * nt + j] * kt[j * nt + l];
      rk[i * nt + l] = s;
    }
  double m = 0.0;
  for (int a = 0; a < nd; ++a) {
    gauss_row(static_cast<double>(a), inv_sd_, qd_, nd, g.data());
    for (int l = 0; l < nt; ++l) {
      double s = 0.0;
      for (int i = 0; i < nd; ++i) s += g[i] * rk[i * nt + l];
      m = std::max(m, s);
    }
  }
  norm_ = m;
  inv_norm_ = m > 0.0 ? 1.0 / m : 0.0;
  stale_ = false;
}

double TaxelMap::parzen(double d, double ttc) const {
  std::array<double, kMaxBinsPerAxis> g, h;
  kernel_d(d, g.data());
  kernel_t(ttc, h.data());
  const int nd = grid_.d_bins, nt = grid_.ttc_bins;
  const double* r = ratio_.data();
  double f = 0.0;
  for (int i = 0; i < nd; ++i) {
    double s = 0.0;
    for (int j = 0; j < nt; ++j) s += r[i * nt + j] * h[j];
    f += g[i] * s;
  }
  return f;
}

double TaxelMap::activation(double d, double ttc) const {
  SOMASIM_CHECK(!stale_, "TaxelMap::activation called with a stale normaliser; call refresh()");
  if (!(d >= grid_.d_min && d <= grid_.d_max && ttc >= grid_.ttc_min && ttc <= grid_.ttc_max))
    return 0.0;
  return std::min(1.0, parzen(d, ttc) * inv_norm_);
}

double TaxelMap::activation_naive(double d, double ttc) const {
  if (!(d >= grid_.d_min && d <= grid_.d_max && ttc >= grid_.ttc_min && ttc <= grid_.ttc_max))
    return 0.0;
  const double sd = parzen_.sigma_scale * grid_.d_width();
  const double st = parzen_.sigma_scale * grid_.ttc_width();
  const double shift = parzen_.anchor == KernelAnchor::kCentre ? 0.5 : 0.0;
  auto f = [&](double x, double y) {
    double s = 0.0;
    for (int i = 0; i < grid_.d_bins; ++i)
      for (int j = 0; j < grid_.ttc_bins; ++j) {
        const std::size_t k = static_cast<std::size_t>(grid_.index(i, j));
        const double tot = static_cast<double>(pos_[k]) + neg_[k];
        const double r = tot > 0 ? pos_[k] / tot : 0.0;
        const double cx = grid_.d_min + (i + shift) * grid_.d_width();
        const double cy = grid_.ttc_min + (j + shift) * grid_.ttc_width();
        s += r *
             std::exp(-0.5 * ((x - cx) * (x - cx) / (sd * sd) + (y - cy) * (y - cy) / (st * st)));
      }
    return s;
  };
  return std::min(1.0, f(d, ttc) * inv_norm_);
}

}  // namespace somasim::pps
