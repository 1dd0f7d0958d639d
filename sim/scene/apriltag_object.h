#pragma once
// AprilTags as scene objects: the tag's bit pattern built from the apriltag library's family
// tables (codes, bit_x/bit_y, width_at_border, total_width, reversed_border), laid out exactly
// like the library's own apriltag_to_image (white ring, black border, data bits), as a
// nearest-filtered texture on a Rectangle.
//
// Size convention (the apriltag library's): tag_size_m is the edge length of the square at the
// black/white border (width_at_border cells). The rectangle spans the whole pattern,
// total_width / width_at_border * tag_size_m, centred on O; the tag's O frame is the OpenCV /
// AprilTag object frame (seen looking along +z_O: x right, y down; see primitives.h).
#include <Eigen/Geometry>
#include <string>

#include "sim/scene/scene.h"

namespace aperture::sim {

// Tag image, total_width x total_width texels, CV_8UC1 (0 black, 255 white).
// family: a library or short name of perception/tags/apriltag_family.h ("tag36h11", "41h12").
// Throws std::invalid_argument for an unknown family or an id outside [0, ncodes).
cv::Mat MakeAprilTagImage(const std::string& family, int id);

// Rectangle object named "tag<id>" showing the tag (white texels albedo 0.95, black 0.05).
SceneObject MakeAprilTagObject(const std::string& family, int id, double tag_size_m,
                               const Eigen::Isometry3d& T_WO);

// Edge length of the full pattern (the rectangle) for a tag of tag_size_m.
double AprilTagPatternSize(const std::string& family, double tag_size_m);

}  // namespace aperture::sim
