#pragma once
/// @file
/// The paper's pose errors (Vicente et al. 2016, eqs 36–39).
#include <Eigen/Geometry>

namespace somasim::body_schema {

/// d_o(R_A, R_B) = ‖logm(R_Aᵀ R_B)‖_F / √2 [deg]: the angle of the relative rotation.
double orientation_error_deg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);
/// Euclidean distance of the two positions [mm] (poses in metres).
double position_error_mm(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

}  // namespace somasim::body_schema
