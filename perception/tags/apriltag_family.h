#pragma once
// AprilTag families of the apriltag library by name (one table for the detector and the
// simulator's tag renderer).
//
// Names are the library's ("tag36h11", "tag25h9", "tag16h5", "tagStandard41h12",
// "tagStandard52h13", "tagCircle21h7", "tagCircle49h12", "tagCustom48h12"); the short forms
// "36h11", "25h9", "16h5", "41h12", "52h13", "21h7", "49h12", "48h12" name the same families.
#include <apriltag/apriltag.h>

#include <memory>
#include <string>
#include <vector>

namespace aperture::perception {

using AprilTagFamilyPtr = std::unique_ptr<apriltag_family_t, void (*)(apriltag_family_t*)>;

// The library name for a library or short name; std::invalid_argument listing the known
// families otherwise.
std::string CanonicalAprilTagFamilyName(const std::string& name);

// A family table owned by the pointer (library or short name, as above).
AprilTagFamilyPtr CreateAprilTagFamily(const std::string& name);

// Every library name, in the order above.
std::vector<std::string> AprilTagFamilyNames();

}  // namespace aperture::perception
