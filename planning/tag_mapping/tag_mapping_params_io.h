#pragma once
// Configuration description (Serialize, config/param_archive.h) of TagMappingParams, the `mission`
// section of `aperture sim tags --mission map` (`--set mission.side_overlap=0.3`): LoadParams
// loads (config/yaml_read_archive.h), config::DumpParams dumps. Keys are the field names; absent
// keys keep the defaults; unknown keys are rejected; the loaded struct is validated.
//
//   mission:
//     min_tag_side_px: 14.0      # height rule: the smallest tag spans at least this
//     side_overlap: 0.5          # of the footprint width shared by adjacent tracks
//     max_speed_mps: 1.0
//     min_segment_duration_s: 1.5
//     settle_s: 1.0
//     camera_id: 0               # the flight sets it to the downward camera's
//     map_odometry: true         # images carry the estimate's camera pose
//     controller: {...}          # control::PositionControllerParams
//     fusion: {filter: {...}, max_consecutive_rejections: 3}
#include "config/yaml_read_archive.h"
#include "control/control_params_io.h"
#include "perception/estimation/pose_fusion_params_io.h"
#include "planning/tag_mapping/tag_mapping_autopilot.h"

namespace aperture::planning {

template <typename Archive>
void Serialize(Archive* a, TagMappingParams* p) {
  a->Visit(APERTURE_NVP(p, min_tag_side_px));
  a->Visit(APERTURE_NVP(p, side_overlap));
  a->Visit(APERTURE_NVP(p, max_speed_mps));
  a->Visit(APERTURE_NVP(p, min_segment_duration_s));
  a->Visit(APERTURE_NVP(p, settle_s));
  a->Visit(APERTURE_NVP(p, camera_id));
  a->Visit(APERTURE_NVP(p, map_odometry));
  a->Visit(APERTURE_NVP(p, controller));
  a->Visit(APERTURE_NVP(p, fusion));
}

}  // namespace aperture::planning
