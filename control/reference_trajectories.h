#pragma once
// Analytic reference trajectories of the thesis experiments, each giving a TrajectoryPoint(t)
// with exact derivatives up to snap (and of the heading):
//  * CircleTrajectory: horizontal circle, radius 1.8 m at 4 m/s (Faessler thesis F.7.2). With a
//    constant heading it needs c = 13.24 m/s^2 and |omega| = 85 deg/s without drag, the thesis
//    figures.
//  * LemniscateTrajectory: horizontal Gerono lemniscate x = 2 cos(phi), y = 2 sin(phi) cos(phi),
//    phi = sqrt(2) t at full speed (F.7.2): maximum speed 4 m/s.
//  * BackAndForthTrajectory: rest-to-rest motion in x alternating direction, each segment the
//    9th-order polynomial whose derivatives 1..4 vanish at both ends (continuous in snap), sized
//    to peak at 12 m/s^2 and 5.7 m/s (thesis G.6.2 experiment, Fig. G.6).
// Circle and lemniscate move along a phase phi(t) given by a PhaseProfile:
//  * kSmooth (default): start from rest, the phase rate rises to full rate along the 9th-order
//    smoothstep over ramp_s (snap stays continuous), stays there for num_loops loops, falls back
//    symmetrically and the vehicle rests at the reached point.
//  * kLinear: the speed ramp of F.7 / Figs. F.6, F.7 ("linearly ramping up the maximum speed from
//    0 m/s to 5 m/s in 30 s"): the phase rate rises linearly from 0 at t = 0 to full rate at
//    ramp_s and then stays; use ThesisSpeedRamp(). As in the thesis the ramp has corners: the
//    phase acceleration steps at t = 0 and t = ramp_s (by 5 m/s / 30 s = 0.17 m/s^2 tangential
//    acceleration on the circle), so jerk and snap are impulses there and are reported as 0.
// Before t = 0 every trajectory rests at its start point. All positions are in W (z up).
#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "control/trajectory_point.h"

namespace aperture::control {

class ReferenceTrajectory {
 public:
  virtual ~ReferenceTrajectory() = default;
  virtual TrajectoryPoint Evaluate(double t_s) const = 0;
  // Time after which the reference is at rest [s] (+infinity when it never stops).
  virtual double EndTimeS() const = 0;
};

struct SpeedRampParams {
  enum class Kind { kSmooth, kLinear };
  Kind kind = Kind::kSmooth;
  // kSmooth: duration of ramp-in and of ramp-out; 3 s keeps the tangential acceleration of the
  // 4 m/s circle below 3.3 m/s^2. kLinear: time to reach full speed (30 s in F.7).
  double ramp_s = 3.0;
  // kSmooth only: loops flown at full speed between the ramps; 10 as in Table F.1.
  double num_loops = 10.0;
};

// Phase phi(t) and its first four derivatives, from a piecewise-polynomial phase rate.
class PhaseProfile {
 public:
  // `rate_radps` is the full phase rate, `period_rad` the phase of one loop (for num_loops).
  // Throws std::invalid_argument for a non-positive rate, ramp time or period, or a negative
  // number of loops.
  PhaseProfile(double rate_radps, double period_rad, const SpeedRampParams& ramp);
  // {phi, phi', phi'', phi''', phi''''} at t.
  std::array<double, 5> Evaluate(double t_s) const;
  double EndTimeS() const { return end_time_s_; }

 private:
  static constexpr int kMaxDegree = 9;
  struct Piece {
    double t_begin_s = 0.0;
    double phase_begin_rad = 0.0;
    std::array<double, kMaxDegree + 1> rate_coeffs{};  // rate(t) = sum c_k (t - t_begin)^k
  };
  void AppendPiece(double t_begin_s, const std::array<double, kMaxDegree + 1>& rate_coeffs);
  std::vector<Piece> pieces_;  // sorted by t_begin_s; the first begins at 0
  double end_time_s_ = 0.0;
};

struct CircleTrajectoryParams {
  Eigen::Vector3d center_W{0.0, 0.0, 1.5};
  double radius_m = 1.8;     // F.7.2
  double speed_mps = 4.0;    // F.7.2
  double heading_rad = 0.0;  // constant heading (the thesis figures assume one)
  SpeedRampParams ramp;
  // F.7 speed ramp: 0 -> 5 m/s linearly in 30 s.
  static CircleTrajectoryParams ThesisSpeedRamp();
};

// p(phi) = center + r [cos phi, sin phi, 0]; starts at center + [r, 0, 0], counter-clockwise.
class CircleTrajectory : public ReferenceTrajectory {
 public:
  explicit CircleTrajectory(const CircleTrajectoryParams& params = {});
  TrajectoryPoint Evaluate(double t_s) const override;
  double EndTimeS() const override { return phase_.EndTimeS(); }

 private:
  CircleTrajectoryParams params_;
  PhaseProfile phase_;
};

struct LemniscateTrajectoryParams {
  Eigen::Vector3d center_W{0.0, 0.0, 1.5};
  double amplitude_m = 2.0;    // F.7.2: x = 2 cos(phi)
  double max_speed_mps = 4.0;  // F.7.2; sets the full phase rate to max_speed / (sqrt(2) A)
  double heading_rad = 0.0;
  SpeedRampParams ramp;
  // F.7 speed ramp: maximum speed 0 -> 5 m/s linearly in 30 s.
  static LemniscateTrajectoryParams ThesisSpeedRamp();
};

// p(phi) = center + A [cos phi, sin phi cos phi, 0]; the speed A |[-sin phi, cos 2phi]| phi' peaks
// at sqrt(2) A phi' where the curve crosses its center.
class LemniscateTrajectory : public ReferenceTrajectory {
 public:
  explicit LemniscateTrajectory(const LemniscateTrajectoryParams& params = {});
  TrajectoryPoint Evaluate(double t_s) const override;
  double EndTimeS() const override { return phase_.EndTimeS(); }

 private:
  LemniscateTrajectoryParams params_;
  PhaseProfile phase_;
};

struct BackAndForthTrajectoryParams {
  Eigen::Vector3d start_W{0.0, 0.0, 1.5};
  double max_speed_mps = 5.7;    // G.6.2
  double max_accel_mps2 = 12.0;  // G.6.2
  int num_round_trips = 12;      // Table G.1 averages over twelve back-and-forth motions
  double dwell_s = 0.0;          // rest between segments (snap stays continuous without it)
  double heading_rad = 0.0;
};

// Segment k moves by +L (k even) or -L (k odd) along x_W in time T with the rest-to-rest
// polynomial S(u) = 126u^5 - 420u^6 + 540u^7 - 315u^8 + 70u^9, u = t/T. Its peaks are
// S'(1/2) = 630/256 and |S''| = 2520 * (3/14)^3 / sqrt(7) at u = (1 -+ 1/sqrt(7))/2, so
//   L/T = v_max / S'max and L/T^2 = a_max / S''max  ->  T = 1.809 s, L = 4.190 m for the defaults.
class BackAndForthTrajectory : public ReferenceTrajectory {
 public:
  explicit BackAndForthTrajectory(const BackAndForthTrajectoryParams& params = {});
  TrajectoryPoint Evaluate(double t_s) const override;
  double EndTimeS() const override;
  double SegmentDurationS() const { return segment_duration_s_; }
  double SegmentLengthM() const { return segment_length_m_; }

 private:
  BackAndForthTrajectoryParams params_;
  double segment_duration_s_ = 0.0;
  double segment_length_m_ = 0.0;
};

// The thesis trajectories with their default parameters, by name: "circle", "lemniscate"
// (F.7.2, smooth ramps), "circle_speed_ramp", "lemniscate_speed_ramp" (F.7.4 linear ramp to
// 5 m/s in 30 s), "back_and_forth" (G.6.2). Throws std::invalid_argument naming the unknown
// name and listing the valid ones.
std::unique_ptr<ReferenceTrajectory> MakeThesisTrajectory(const std::string& name);

}  // namespace aperture::control
