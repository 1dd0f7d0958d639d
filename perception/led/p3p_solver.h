#pragma once
// Perspective-three-point: the up to four poses T_CT of a target whose points p_T [m] are seen
// along the unit bearings f_C. Interchangeable solvers (Faessler thesis C.3.4 uses Kneip's):
//   kKneip   Kneip, Scaramuzza, Siegwart, CVPR 2011, implemented here: the quartic's real roots
//            by Ferrari's method in real arithmetic, no allocation (any bearing, also > 90 deg).
//            The default.
//   kOpenGv  the same method through OpenGV (complex quartic roots, allocations), as reference
//   kAp3p    Ke & Roumeliotis, CVPR 2017, through cv::solveP3P(SOLVEPNP_AP3P) (bearings in front
//            of the camera only, f_C.z() > 0; others give no solution)
// Degenerate input (collinear points, parallel bearings) returns no or fewer solutions; the
// caller verifies candidates by reprojection. OpenGV stays inside the .cc.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace aperture::perception {

enum class P3pMethod { kKneip, kOpenGv, kAp3p };

// "kneip" | "opengv" | "ap3p"; throws std::invalid_argument naming the value otherwise.
P3pMethod ParseP3pMethod(const std::string& name);
std::string P3pMethodName(P3pMethod method);

// Appends the solutions T_CT (p_C = T_CT * p_T) to *solutions (cleared first).
void SolveP3p(P3pMethod method, const std::array<Eigen::Vector3d, 3>& f_C,
              const std::array<Eigen::Vector3d, 3>& p_T, std::vector<Eigen::Isometry3d>* solutions);

}  // namespace aperture::perception
