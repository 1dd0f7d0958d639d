#pragma once
// YAML loaders (config::ParamReader, STYLE.md 6) for the `apriltag` front end. Keys are the field
// names; absent keys keep the in-class defaults; unknown keys are rejected.
//
//   apriltag:
//     detector: apriltag            # TagDetectorRegistry name: apriltag | visp (when linked)
//     families: [tag36h11]          # library or short names (36h11, 16h5, 25h9, 41h12, ...)
//     quad_decimate: 2.0
//     quad_sigma: 0.0
//     min_white_black_diff: 20      # local contrast [gray levels] the threshold segments
//     threads: 1
//     refine_edges: true
//     decode_sharpening: 0.25
//     max_hamming: 2
//     min_decision_margin: 0.0
//     size_m: 0.25                  # edge of the black border [m], every tag ...
//     sizes: {6: 0.1, 7: 0.1}       # ... unless listed here by id
//     corner_sigma_px: 1.0          # corner noise for the pose covariance
//     flip: {enabled: true, max_ambiguity_ratio: 0.25, min_error_gap_px2: 0.25,
//            coplanar_tolerance_deg: 15, max_track_gap_s: 0.5}
//     map: false                    # build the tag map (tag_map.yaml, tag_map.png)
//     mapping: {origin_id: 0, origin_p_m: [0, 0, 0], origin_rpy_deg: [180, 0, 0],
//               floor_sigma_m: 0.002, floor_sigma_rad: 0.005, gravity_sigma_deg: 1.0,
//               odometry_sigma_m_per_sqrt_m: 0.03, odometry_sigma_deg_per_sqrt_m: 0.3,
//               odometry_floor_sigma_m: 0.001, odometry_floor_sigma_deg: 0.05,
//               huber_scale: 2.0,
//               outlier_chi2: 22.46, solve_every: 10, incremental_iterations: 5,
//               max_iterations: 100, max_pending_images: 1000}
#include "config/param_reader.h"
#include "perception/tags/tag_front_end.h"
#include "perception/tags/tag_map.h"

namespace aperture::perception {

void LoadParams(config::ParamReader& reader, TagDetectorParams* params);
void LoadParams(config::ParamReader& reader, TagFlipResolverParams* params);
void LoadParams(config::ParamReader& reader, TagMapParams* params);
// The front end's keys (the detector's are flat in the same section). Validates.
void LoadParams(config::ParamReader& reader, TagFrontEndParams* params);

}  // namespace aperture::perception
