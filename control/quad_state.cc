#include "control/quad_state.h"

#include <cmath>

namespace aperture::control {

bool QuadState::IsValid() const {
  return std::isfinite(t_s) && p_WB.allFinite() && v_W.allFinite() && omega_B.allFinite() &&
         q_WB.coeffs().allFinite() && std::abs(q_WB.norm() - 1.0) < 1e-6;
}

}  // namespace aperture::control
