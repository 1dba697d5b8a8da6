#pragma once
// Counts of taxels 3 (left forearm) and 101 (right palm) of the iCub file
// taxels2D_learned_rightHandLeftForearm.ini (Dec 2014), D-major (index = d_bin * 4 + ttc_bin),
// and the reference activations from the shared data README (code variant: sigma = 0.75 bin,
// lower-edge anchors, TTC in [0, 1.2] s).
#include <array>
#include <cstdint>
#include <vector>

namespace pps_ref {

inline const std::vector<std::uint32_t> kTaxel3Pos = {
    1, 0,   1,   1, 0, 0, 0,  0,  510, 112, 76, 40, 136, 290, 6, 2,
    2, 107, 136, 5, 1, 8, 31, 21, 1,   0,   5,  11, 0,   0,   1, 4};
inline const std::vector<std::uint32_t> kTaxel3Neg = {
    4,  14,  12,  1,  16, 33, 2,  0,  377, 74, 29, 15, 217, 295, 21, 10,
    12, 178, 170, 22, 0,  20, 52, 46, 0,   4,  20, 31, 2,   0,   2,  16};
inline const std::vector<std::uint32_t> kTaxel101Pos = {1,  0,  0,  2, 2,  4,  5,  3,  25, 5, 2,
                                                        0,  49, 28, 4, 1,  4,  38, 26, 9,  0, 19,
                                                        12, 22, 0,  4, 16, 23, 0,  1,  4,  17};
inline const std::vector<std::uint32_t> kTaxel101Neg = {2,  2,  2,  11, 1,  6,  9,  13, 59, 13, 6,
                                                        4,  89, 67, 16, 8,  3,  71, 43, 10, 1,  24,
                                                        41, 24, 0,  4,  29, 28, 0,  0,  11, 21};

struct Point {
  double d, ttc;
};
inline constexpr std::array<Point, 6> kPoints = {
    {{0.0, 0.0}, {0.02, 0.15}, {0.05, 0.3}, {0.10, 0.6}, {0.15, 0.9}, {0.19, 1.1}}};
inline constexpr std::array<double, 6> kTaxel3Act = {0.700, 0.789, 0.789, 0.589, 0.343, 0.068};
inline constexpr std::array<double, 6> kTaxel101Act = {0.668, 0.814, 0.871, 0.906, 0.705, 0.160};

}  // namespace pps_ref
