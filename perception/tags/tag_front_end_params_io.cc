#include "perception/tags/tag_front_end_params_io.h"

#include <stdexcept>

namespace aperture::perception {

void LoadParams(config::ParamReader& reader, TagDetectorParams* params) {
  reader.Read("families", &params->families);
  reader.Read("quad_decimate", &params->quad_decimate);
  reader.Read("quad_sigma", &params->quad_sigma);
  reader.Read("min_white_black_diff", &params->min_white_black_diff);
  reader.Read("threads", &params->threads);
  reader.Read("refine_edges", &params->refine_edges);
  reader.Read("decode_sharpening", &params->decode_sharpening);
  reader.Read("max_hamming", &params->max_hamming);
  reader.Read("min_decision_margin", &params->min_decision_margin);
}

void LoadParams(config::ParamReader& reader, TagFlipResolverParams* params) {
  reader.Read("enabled", &params->enabled);
  reader.Read("max_ambiguity_ratio", &params->max_ambiguity_ratio);
  reader.Read("min_error_gap_px2", &params->min_error_gap_px2);
  reader.Read("coplanar_tolerance_deg", &params->coplanar_tolerance_deg);
  reader.Read("max_track_gap_s", &params->max_track_gap_s);
}

void LoadParams(config::ParamReader& reader, TagMapParams* params) {
  reader.Read("origin_id", &params->origin_id);
  reader.Read("origin_p_m", &params->origin_p_m);
  reader.Read("origin_rpy_deg", &params->origin_rpy_deg);
  reader.Read("floor_sigma_m", &params->floor_sigma_m);
  reader.Read("floor_sigma_rad", &params->floor_sigma_rad);
  reader.Read("gravity_sigma_deg", &params->gravity_sigma_deg);
  reader.Read("odometry_sigma_m_per_sqrt_m", &params->odometry_sigma_m_per_sqrt_m);
  reader.Read("odometry_sigma_deg_per_sqrt_m", &params->odometry_sigma_deg_per_sqrt_m);
  reader.Read("odometry_floor_sigma_m", &params->odometry_floor_sigma_m);
  reader.Read("odometry_floor_sigma_deg", &params->odometry_floor_sigma_deg);
  reader.Read("huber_scale", &params->huber_scale);
  reader.Read("outlier_chi2", &params->outlier_chi2);
  reader.Read("solve_every", &params->solve_every);
  reader.Read("incremental_iterations", &params->incremental_iterations);
  reader.Read("max_iterations", &params->max_iterations);
  reader.Read("max_pending_images", &params->max_pending_images);
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, TagFrontEndParams* params) {
  reader.Read("detector", &params->detector);
  LoadParams(reader, &params->detection);
  reader.Read("size_m", &params->size_m);
  config::ParamReader sizes = reader.Section("sizes");
  for (const std::string& key : sizes.Keys()) {
    std::size_t used = 0;
    int id = -1;
    try {
      id = std::stoi(key, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != key.size() || id < 0) {
      sizes.Fail(key, "is not a tag id: the keys of apriltag.sizes are tag ids (0, 1, ...)");
    }
    double size = 0.0;
    sizes.Read(key, &size);
    params->sizes[id] = size;
  }
  reader.Read("corner_sigma_px", &params->pose.refiner.detection_sigma_px);
  reader.ReadSection("flip", &params->flip);
  reader.Validate(*params);
}

}  // namespace aperture::perception
