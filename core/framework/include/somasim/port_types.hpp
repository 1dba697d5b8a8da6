#pragma once
/// @file
/// The framework's own port value types: scalars and 3-vectors. Domain libraries declare theirs
/// beside their code (somasim/robot/ports.hpp, somasim/skin/ports.hpp, somasim/pps/ports.hpp);
/// plugins may define their own types the same way (specialise PortTraits).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "somasim/port_type.hpp"

namespace somasim {

template <>
struct PortTraits<double> {
  static constexpr const char* name = "scalar";
  static constexpr const char* header = "somasim/port_types.hpp";
  static std::vector<std::string> csv_columns(const double&) { return {"value"}; }
  static void csv_write(const double& v, std::string& row) { csv_append(row, v); }
};

template <>
struct PortTraits<Eigen::Vector3d> {
  static constexpr const char* name = "vector3";
  static constexpr const char* header = "somasim/port_types.hpp";
  static std::vector<std::string> csv_columns(const Eigen::Vector3d&) { return {"x", "y", "z"}; }
  static void csv_write(const Eigen::Vector3d& v, std::string& row) {
    for (int i = 0; i < 3; ++i) csv_append(row, v[i]);
  }
};

}  // namespace somasim
