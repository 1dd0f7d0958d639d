#include "experiments/gap/gap_trial_record_json.h"

#include <stdexcept>

#include "control/constants.h"
#include "output/json_eigen.h"

namespace aperture::experiments {
namespace {

// QuadState as [t_s, p_WB (3), v_W (3), q_WB (w, x, y, z), omega_B (3)].
constexpr int kQuadStateSize = 14;

nlohmann::json QuadStateToJson(const control::QuadState& s) {
  return {s.t_s,      s.p_WB.x(),    s.p_WB.y(),    s.p_WB.z(),   s.v_W.x(),
          s.v_W.y(),  s.v_W.z(),     s.q_WB.w(),    s.q_WB.x(),   s.q_WB.y(),
          s.q_WB.z(), s.omega_B.x(), s.omega_B.y(), s.omega_B.z()};
}

control::QuadState QuadStateFromJson(const nlohmann::json& j) {
  if (!j.is_array() || j.size() != kQuadStateSize) {
    throw std::invalid_argument("gap trial record: a state must be an array of " +
                                std::to_string(kQuadStateSize) + " numbers, got " + j.dump());
  }
  const auto at = [&](int i) { return j[static_cast<std::size_t>(i)].get<double>(); };
  control::QuadState s;
  s.t_s = at(0);
  s.p_WB = Eigen::Vector3d(at(1), at(2), at(3));
  s.v_W = Eigen::Vector3d(at(4), at(5), at(6));
  s.q_WB = Eigen::Quaterniond(at(7), at(8), at(9), at(10));
  s.omega_B = Eigen::Vector3d(at(11), at(12), at(13));
  return s;
}

nlohmann::json TraceToJson(const std::vector<control::QuadState>& trace) {
  nlohmann::json json = nlohmann::json::array();
  for (const control::QuadState& s : trace) json.push_back(QuadStateToJson(s));
  return json;
}

std::vector<control::QuadState> TraceFromJson(const nlohmann::json& json) {
  std::vector<control::QuadState> trace;
  trace.reserve(json.size());
  for (const nlohmann::json& s : json) trace.push_back(QuadStateFromJson(s));
  return trace;
}

}  // namespace

nlohmann::json GapStateErrorToJson(const GapStateError& error) {
  return {{"position_m", output::EigenToJson(error.position_m)},
          {"velocity_mps", output::EigenToJson(error.velocity_mps)},
          {"orientation_deg", output::EigenToJson(error.orientation_deg)},
          {"time_s", error.time_s}};
}

GapStateError GapStateErrorFromJson(const nlohmann::json& j) {
  GapStateError error;
  error.position_m = output::JsonToVector<3>(j.at("position_m"));
  error.velocity_mps = output::JsonToVector<3>(j.at("velocity_mps"));
  error.orientation_deg = output::JsonToVector<2>(j.at("orientation_deg"));
  error.time_s = j.at("time_s").is_null() ? control::kNaN : j.at("time_s").get<double>();
  return error;
}

nlohmann::json GapTrialSummaryJson(const GapTrialRecord& record) {
  const GapTrialConfig& c = record.config;
  nlohmann::json trial = {
      {"trial", c.index},
      {"seed", c.seed},
      {"roll_deg", c.roll_deg},
      {"pitch_deg", c.pitch_deg},
      {"start_p_W_m", output::EigenToJson(c.start_p_W)},
      {"start_yaw_deg", c.start_yaw_deg},
      {"imu_noise_scale", c.imu_noise_scale},
      {"accel_bias_B_mps2", output::EigenToJson(c.accel_bias_B)},
      {"gyro_bias_B_radps", output::EigenToJson(c.gyro_bias_B)},
      {"drop_probability", c.drop_probability},
      {"exposure_s", c.exposure_s},
      {"outcome", record.outcome},
      {"success", record.evaluation.success},
      {"failure_reason", record.evaluation.failure_reason},
      {"sim_time_s", record.sim_time_s},
      {"wall_time_s", record.wall_time_s},
      {"autopilot_status", record.autopilot_status},
      {"frames_delivered", record.frames_delivered},
      {"frames_dropped", record.frames_dropped},
      {"frames_skipped", record.frames_skipped},
      {"traverse_start_time_s", record.traverse_start_time_s},
  };
  if (const std::optional<GapCrossing>& crossing = record.evaluation.crossing) {
    trial["crossing"] = {{"t_s", crossing->t_s},
                         {"p_G_m", output::EigenToJson(crossing->p_G_m)},
                         {"inside_opening", crossing->inside_opening}};
  }
  const GapTrialEvaluation& evaluation = record.evaluation;
  if (evaluation.error) trial["error_at_gap"] = GapStateErrorToJson(*evaluation.error);
  if (evaluation.error_at_planned_tc) {
    trial["error_at_planned_tc"] = GapStateErrorToJson(*evaluation.error_at_planned_tc);
  }
  if (const std::optional<FootprintContact>& contact = evaluation.footprint_contact) {
    trial["footprint_contact"] = {{"t_s", contact->t_s},
                                  {"part", contact->part},
                                  {"p_G_m", output::EigenToJson(contact->p_G_m)}};
  }
  return trial;
}

nlohmann::json GapTrialRecordToJson(const GapTrialRecord& record) {
  nlohmann::json json = GapTrialSummaryJson(record);
  json["motion_blur_subframes"] = record.config.motion_blur_subframes;
  json["autopilot_name"] = record.autopilot_name;
  if (record.evaluation.crossing) {
    json["crossing"]["state"] = QuadStateToJson(record.evaluation.crossing->state);
  }
  json["estimate_trace"] = TraceToJson(record.estimate_trace);
  json["truth_trace"] = TraceToJson(record.truth_trace);
  json["cpu_profile"] = record.cpu_profile;
  return json;
}

GapTrialRecord GapTrialRecordFromJson(const nlohmann::json& json) {
  try {
    GapTrialRecord r;
    GapTrialConfig& c = r.config;
    c.index = json.at("trial").get<int>();
    c.seed = json.at("seed").get<std::uint64_t>();
    c.roll_deg = json.at("roll_deg").get<double>();
    c.pitch_deg = json.at("pitch_deg").get<double>();
    c.start_p_W = output::JsonToVector<3>(json.at("start_p_W_m"));
    c.start_yaw_deg = json.at("start_yaw_deg").get<double>();
    c.imu_noise_scale = json.at("imu_noise_scale").get<double>();
    c.accel_bias_B = output::JsonToVector<3>(json.at("accel_bias_B_mps2"));
    c.gyro_bias_B = output::JsonToVector<3>(json.at("gyro_bias_B_radps"));
    c.drop_probability = json.at("drop_probability").get<double>();
    c.exposure_s = json.at("exposure_s").get<double>();
    c.motion_blur_subframes = json.at("motion_blur_subframes").get<int>();
    r.outcome = json.at("outcome").get<std::string>();
    r.evaluation.success = json.at("success").get<bool>();
    r.evaluation.failure_reason = json.at("failure_reason").get<std::string>();
    r.sim_time_s = json.at("sim_time_s").get<double>();
    r.wall_time_s = json.at("wall_time_s").get<double>();
    r.autopilot_name = json.at("autopilot_name").get<std::string>();
    r.autopilot_status = json.at("autopilot_status").get<std::string>();
    r.frames_delivered = json.at("frames_delivered").get<int>();
    r.frames_dropped = json.at("frames_dropped").get<int>();
    r.frames_skipped = json.at("frames_skipped").get<int>();
    r.traverse_start_time_s = json.at("traverse_start_time_s").get<double>();
    if (json.contains("crossing")) {
      const nlohmann::json& j = json["crossing"];
      GapCrossing crossing;
      crossing.t_s = j.at("t_s").get<double>();
      crossing.state = QuadStateFromJson(j.at("state"));
      crossing.p_G_m = output::JsonToVector<2>(j.at("p_G_m"));
      crossing.inside_opening = j.at("inside_opening").get<bool>();
      r.evaluation.crossing = crossing;
    }
    if (json.contains("error_at_gap")) {
      r.evaluation.error = GapStateErrorFromJson(json["error_at_gap"]);
    }
    if (json.contains("error_at_planned_tc")) {
      r.evaluation.error_at_planned_tc = GapStateErrorFromJson(json["error_at_planned_tc"]);
    }
    if (json.contains("footprint_contact")) {
      const nlohmann::json& j = json["footprint_contact"];
      r.evaluation.footprint_contact =
          FootprintContact{j.at("t_s").get<double>(), j.at("part").get<std::string>(),
                           output::JsonToVector<2>(j.at("p_G_m"))};
    }
    r.estimate_trace = TraceFromJson(json.at("estimate_trace"));
    r.truth_trace = TraceFromJson(json.at("truth_trace"));
    r.cpu_profile = json.value("cpu_profile", nlohmann::json());
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("gap trial record: ") + e.what());
  }
}

}  // namespace aperture::experiments
