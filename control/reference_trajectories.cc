#include "control/reference_trajectories.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "control/require.h"

namespace aperture::control {
namespace {

constexpr int kDegree = 9;
using Coeffs = std::array<double, kDegree + 1>;

// 9th-order smoothstep: S(0) = 0, S(1) = 1, derivatives 1..4 vanish at both ends.
constexpr Coeffs kSmoothstep9 = {0.0, 0.0, 0.0, 0.0, 0.0, 126.0, -420.0, 540.0, -315.0, 70.0};
// Peaks of S' and |S''| on [0, 1] (closed forms in the header).
const double kSmoothstepMaxRate = 630.0 / 256.0;
const double kSmoothstepMaxAccel = 2520.0 * std::pow(3.0 / 14.0, 3) / std::sqrt(7.0);

// d^order/dx^order of sum_k c_k x^k.
double PolynomialDerivative(const Coeffs& c, double x, int order) {
  double value = 0.0;
  for (int k = kDegree; k >= order; --k) {
    double factor = 1.0;
    for (int m = 0; m < order; ++m) factor *= static_cast<double>(k - m);
    value = value * x + factor * c[k];
  }
  return value;
}

// Phase rate [rad/s] at which a path with |dp/dphi| peaking at `length_m` reaches `speed_mps`.
double FullPhaseRate(double speed_mps, double length_m, const std::string& speed_name,
                     const std::string& length_name) {
  RequirePositive(speed_mps, speed_name);
  RequirePositive(length_m, length_name);
  return speed_mps / length_m;
}

// Chain rule (Faa di Bruno up to 4th order) for p(phi(t)): path derivatives dp^k/dphi^k and phase
// derivatives {phi, phi', ..., phi''''}.
TrajectoryPoint ComposeWithPhase(double t_s, const std::array<Eigen::Vector3d, 5>& P,
                                 const std::array<double, 5>& f, double heading_rad) {
  const double f1 = f[1], f2 = f[2], f3 = f[3], f4 = f[4];
  TrajectoryPoint point;
  point.t_s = t_s;
  point.p_W = P[0];
  point.v_W = P[1] * f1;
  point.a_W = P[2] * (f1 * f1) + P[1] * f2;
  point.j_W = P[3] * (f1 * f1 * f1) + P[2] * (3.0 * f1 * f2) + P[1] * f3;
  point.s_W = P[4] * (f1 * f1 * f1 * f1) + P[3] * (6.0 * f1 * f1 * f2) +
              P[2] * (3.0 * f2 * f2 + 4.0 * f1 * f3) + P[1] * f4;
  point.heading_rad = heading_rad;
  return point;
}

}  // namespace

// ---------------------------------------------------------------------------- PhaseProfile

PhaseProfile::PhaseProfile(double rate_radps, double period_rad, const SpeedRampParams& ramp) {
  RequirePositive(rate_radps, "PhaseProfile: full phase rate [rad/s]");
  RequirePositive(period_rad, "PhaseProfile: loop period [rad]");
  RequirePositive(ramp.ramp_s, "SpeedRampParams::ramp_s");
  const double tr = ramp.ramp_s;
  if (ramp.kind == SpeedRampParams::Kind::kLinear) {
    AppendPiece(0.0, Coeffs{0.0, rate_radps / tr});
    AppendPiece(tr, Coeffs{rate_radps});
    end_time_s_ = std::numeric_limits<double>::infinity();
    return;
  }
  if (!(ramp.num_loops >= 0.0) || !std::isfinite(ramp.num_loops)) {
    throw std::invalid_argument("SpeedRampParams::num_loops = " + std::to_string(ramp.num_loops) +
                                " must be finite and >= 0");
  }
  Coeffs ramp_in{}, ramp_out{};
  double scale = rate_radps;
  for (int k = 0; k <= kDegree; ++k) {
    ramp_in[k] = scale * kSmoothstep9[k];
    ramp_out[k] = -ramp_in[k];  // S(1 - u) = 1 - S(u)
    scale /= tr;
  }
  ramp_out[0] += rate_radps;
  const double cruise_s = ramp.num_loops * period_rad / rate_radps;
  AppendPiece(0.0, ramp_in);
  AppendPiece(tr, Coeffs{rate_radps});
  AppendPiece(tr + cruise_s, ramp_out);
  AppendPiece(2.0 * tr + cruise_s, Coeffs{});
  end_time_s_ = 2.0 * tr + cruise_s;
}

void PhaseProfile::AppendPiece(double t_begin_s, const Coeffs& rate_coeffs) {
  Piece piece;
  piece.t_begin_s = t_begin_s;
  piece.rate_coeffs = rate_coeffs;
  if (!pieces_.empty()) {
    const Piece& last = pieces_.back();
    const double tau = t_begin_s - last.t_begin_s;
    double integral = 0.0;
    for (int k = kDegree; k >= 0; --k) integral = integral * tau + last.rate_coeffs[k] / (k + 1);
    piece.phase_begin_rad = last.phase_begin_rad + integral * tau;
  }
  pieces_.push_back(piece);
}

std::array<double, 5> PhaseProfile::Evaluate(double t_s) const {
  std::array<double, 5> f{};
  if (t_s < 0.0) return f;  // at rest at phase 0 before the start
  const Piece* piece = &pieces_.front();
  for (const Piece& candidate : pieces_) {
    if (candidate.t_begin_s <= t_s) piece = &candidate;
  }
  const double tau = t_s - piece->t_begin_s;
  double integral = 0.0;
  for (int k = kDegree; k >= 0; --k) integral = integral * tau + piece->rate_coeffs[k] / (k + 1);
  f[0] = piece->phase_begin_rad + integral * tau;
  for (int order = 0; order < 4; ++order) {
    f[order + 1] = PolynomialDerivative(piece->rate_coeffs, tau, order);
  }
  return f;
}

// ---------------------------------------------------------------------------- Circle

CircleTrajectoryParams CircleTrajectoryParams::ThesisSpeedRamp() {
  CircleTrajectoryParams params;
  params.speed_mps = 5.0;
  params.ramp.kind = SpeedRampParams::Kind::kLinear;
  params.ramp.ramp_s = 30.0;
  return params;
}

CircleTrajectory::CircleTrajectory(const CircleTrajectoryParams& params)
    : params_(params),
      phase_(FullPhaseRate(params.speed_mps, params.radius_m, "CircleTrajectoryParams::speed_mps",
                           "CircleTrajectoryParams::radius_m"),
             2.0 * M_PI, params.ramp) {
  RequireFinite(params.center_W, "CircleTrajectoryParams::center_W");
}

TrajectoryPoint CircleTrajectory::Evaluate(double t_s) const {
  const std::array<double, 5> f = phase_.Evaluate(t_s);
  const double r = params_.radius_m;
  const Eigen::Vector3d u(std::cos(f[0]), std::sin(f[0]), 0.0);  // d^0, d^4
  const Eigen::Vector3d u1(-u.y(), u.x(), 0.0);                  // d^1 (and -d^3)
  const std::array<Eigen::Vector3d, 5> P = {params_.center_W + r * u, r * u1, -r * u, -r * u1,
                                            r * u};
  return ComposeWithPhase(t_s, P, f, params_.heading_rad);
}

// ---------------------------------------------------------------------------- Lemniscate

LemniscateTrajectoryParams LemniscateTrajectoryParams::ThesisSpeedRamp() {
  LemniscateTrajectoryParams params;
  params.max_speed_mps = 5.0;
  params.ramp.kind = SpeedRampParams::Kind::kLinear;
  params.ramp.ramp_s = 30.0;
  return params;
}

LemniscateTrajectory::LemniscateTrajectory(const LemniscateTrajectoryParams& params)
    : params_(params),
      // The lemniscate speed A |[-sin phi, cos 2 phi]| phi' peaks at sqrt(2) A phi'.
      phase_(FullPhaseRate(params.max_speed_mps, std::sqrt(2.0) * params.amplitude_m,
                           "LemniscateTrajectoryParams::max_speed_mps",
                           "LemniscateTrajectoryParams::amplitude_m"),
             2.0 * M_PI, params.ramp) {
  RequireFinite(params.center_W, "LemniscateTrajectoryParams::center_W");
}

TrajectoryPoint LemniscateTrajectory::Evaluate(double t_s) const {
  const std::array<double, 5> f = phase_.Evaluate(t_s);
  const double A = params_.amplitude_m;
  const double c1 = std::cos(f[0]), s1 = std::sin(f[0]);
  const double c2 = std::cos(2.0 * f[0]), s2 = std::sin(2.0 * f[0]);
  // x = A cos(phi), y = (A / 2) sin(2 phi).
  const std::array<Eigen::Vector3d, 5> P = {
      params_.center_W + Eigen::Vector3d(A * c1, 0.5 * A * s2, 0.0),
      Eigen::Vector3d(-A * s1, A * c2, 0.0), Eigen::Vector3d(-A * c1, -2.0 * A * s2, 0.0),
      Eigen::Vector3d(A * s1, -4.0 * A * c2, 0.0), Eigen::Vector3d(A * c1, 8.0 * A * s2, 0.0)};
  return ComposeWithPhase(t_s, P, f, params_.heading_rad);
}

// ---------------------------------------------------------------------------- Back and forth

BackAndForthTrajectory::BackAndForthTrajectory(const BackAndForthTrajectoryParams& params)
    : params_(params) {
  RequireFinite(params.start_W, "BackAndForthTrajectoryParams::start_W");
  RequirePositive(params.max_speed_mps, "BackAndForthTrajectoryParams::max_speed_mps");
  RequirePositive(params.max_accel_mps2, "BackAndForthTrajectoryParams::max_accel_mps2");
  if (params.num_round_trips < 0) {
    throw std::invalid_argument("BackAndForthTrajectoryParams::num_round_trips = " +
                                std::to_string(params.num_round_trips) + " must be >= 0");
  }
  if (!(params.dwell_s >= 0.0) || !std::isfinite(params.dwell_s)) {
    throw std::invalid_argument("BackAndForthTrajectoryParams::dwell_s = " +
                                std::to_string(params.dwell_s) + " must be finite and >= 0");
  }
  segment_duration_s_ =
      params.max_speed_mps * kSmoothstepMaxAccel / (params.max_accel_mps2 * kSmoothstepMaxRate);
  segment_length_m_ = params.max_speed_mps * segment_duration_s_ / kSmoothstepMaxRate;
}

double BackAndForthTrajectory::EndTimeS() const {
  return 2.0 * params_.num_round_trips * (segment_duration_s_ + params_.dwell_s);
}

TrajectoryPoint BackAndForthTrajectory::Evaluate(double t_s) const {
  TrajectoryPoint point;
  point.t_s = t_s;
  point.p_W = params_.start_W;
  point.heading_rad = params_.heading_rad;
  if (t_s < 0.0 || t_s >= EndTimeS()) return point;
  const double period_s = segment_duration_s_ + params_.dwell_s;
  const int segment = static_cast<int>(std::floor(t_s / period_s));
  const double tau = std::min(t_s - segment * period_s, segment_duration_s_);
  const double sign = (segment % 2 == 0) ? 1.0 : -1.0;
  const double x_begin = (segment % 2 == 0) ? 0.0 : segment_length_m_;
  const double u = tau / segment_duration_s_;
  double scale = sign * segment_length_m_;
  std::array<double, 5> x{};
  for (int order = 0; order <= 4; ++order) {
    x[order] = scale * PolynomialDerivative(kSmoothstep9, u, order);
    scale /= segment_duration_s_;
  }
  point.p_W.x() += x_begin + x[0];
  point.v_W.x() = x[1];
  point.a_W.x() = x[2];
  point.j_W.x() = x[3];
  point.s_W.x() = x[4];
  return point;
}

// ---------------------------------------------------------------------------- By name

std::unique_ptr<ReferenceTrajectory> MakeThesisTrajectory(const std::string& name) {
  if (name == "circle") return std::make_unique<CircleTrajectory>();
  if (name == "lemniscate") return std::make_unique<LemniscateTrajectory>();
  if (name == "circle_speed_ramp") {
    return std::make_unique<CircleTrajectory>(CircleTrajectoryParams::ThesisSpeedRamp());
  }
  if (name == "lemniscate_speed_ramp") {
    return std::make_unique<LemniscateTrajectory>(LemniscateTrajectoryParams::ThesisSpeedRamp());
  }
  if (name == "back_and_forth") return std::make_unique<BackAndForthTrajectory>();
  throw std::invalid_argument("unknown reference trajectory '" + name +
                              "'; use one of circle, lemniscate, circle_speed_ramp, "
                              "lemniscate_speed_ramp, back_and_forth");
}

}  // namespace aperture::control
