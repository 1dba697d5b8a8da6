#pragma once
// Helpers shared by the robot tests: the shipped iCub descriptions and a standalone DH chain.
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/robot/robot_loader.hpp"

namespace somasim::robot::test {

inline RobotModel load_icub(const std::string& variant = "icub_v1") {
  return load_robot_model(std::string(SOMASIM_SOURCE_DIR) + "/assets/robots/" + variant + ".yaml");
}

inline constexpr double kDeg = M_PI / 180.0;

/// One iKin DH row [m, deg].
struct DhRow {
  double a, d, alpha_deg, offset_deg;
};

/// Standalone iKin FK: H0 · Π Rz(q_i + offset_i)·Tz(d_i)·Tx(a_i)·Rx(alpha_i), q in rad.
inline Eigen::Matrix4d dh_forward(const std::vector<DhRow>& rows, const Eigen::VectorXd& q) {
  Eigen::Matrix4d t;
  t << 0, -1, 0, 0, 0, 0, -1, 0, 1, 0, 0, 0, 0, 0, 0, 1;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double th = q[static_cast<Eigen::Index>(i)] + rows[i].offset_deg * kDeg;
    const double al = rows[i].alpha_deg * kDeg;
    Eigen::Matrix4d m;
    m << std::cos(th), -std::sin(th) * std::cos(al), std::sin(th) * std::sin(al),
        rows[i].a * std::cos(th), std::sin(th), std::cos(th) * std::cos(al),
        -std::cos(th) * std::sin(al), rows[i].a * std::sin(th), 0, std::sin(al), std::cos(al),
        rows[i].d, 0, 0, 0, 1;
    t = t * m;
  }
  return t;
}

inline const std::vector<DhRow> kLeftArmV1 = {
    {0.032, 0, 90, 0},     {0, -0.0055, 90, -90}, {0.0233647, -0.1433, -90, 105},
    {0, 0.10774, -90, 90}, {0, 0, 90, -90},       {0.015, 0.15228, -90, 75},
    {-0.015, 0, 90, 0},    {0, 0.1373, 90, -90},  {0, 0, 90, 90},
    {0.0625, -0.016, 0, 0}};
inline const std::vector<DhRow> kRightArmV1 = {
    {0.032, 0, 90, 0},      {0, -0.0055, 90, -90}, {-0.0233647, -0.1433, 90, -105},
    {0, -0.10774, 90, -90}, {0, 0, -90, -90},      {-0.015, -0.15228, -90, -105},
    {0.015, 0, 90, 0},      {0, -0.1373, 90, -90}, {0, 0, 90, 90},
    {0.0625, 0.016, 0, 180}};
inline const std::vector<DhRow> kLeftEyeV1 = {
    {0.032, 0, 90, 0},   {0, -0.0055, 90, -90}, {0.00231, -0.1933, -90, -90},
    {0.033, 0, 90, 90},  {0, 0.001, -90, -90},  {-0.054, 0.0825, -90, 90},
    {0, -0.034, -90, 0}, {0, 0, 90, -90}};
inline const std::vector<DhRow> kRightEyeV1 = {
    {0.032, 0, 90, 0},  {0, -0.0055, 90, -90}, {0.00231, -0.1933, -90, -90},
    {0.033, 0, 90, 90}, {0, 0.001, -90, -90},  {-0.054, 0.0825, -90, 90},
    {0, 0.034, -90, 0}, {0, 0, 90, -90}};

}  // namespace somasim::robot::test
