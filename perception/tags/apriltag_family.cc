#include "perception/tags/apriltag_family.h"

#include <apriltag/tag16h5.h>
#include <apriltag/tag25h9.h>
#include <apriltag/tag36h11.h>
#include <apriltag/tagCircle21h7.h>
#include <apriltag/tagCircle49h12.h>
#include <apriltag/tagCustom48h12.h>
#include <apriltag/tagStandard41h12.h>
#include <apriltag/tagStandard52h13.h>

#include <stdexcept>

namespace aperture::perception {
namespace {

struct FamilyFunctions {
  const char* name;
  const char* short_name;
  apriltag_family_t* (*create)();
  void (*destroy)(apriltag_family_t*);
};

constexpr FamilyFunctions kFamilies[] = {
    {"tag36h11", "36h11", tag36h11_create, tag36h11_destroy},
    {"tag25h9", "25h9", tag25h9_create, tag25h9_destroy},
    {"tag16h5", "16h5", tag16h5_create, tag16h5_destroy},
    {"tagStandard41h12", "41h12", tagStandard41h12_create, tagStandard41h12_destroy},
    {"tagStandard52h13", "52h13", tagStandard52h13_create, tagStandard52h13_destroy},
    {"tagCircle21h7", "21h7", tagCircle21h7_create, tagCircle21h7_destroy},
    {"tagCircle49h12", "49h12", tagCircle49h12_create, tagCircle49h12_destroy},
    {"tagCustom48h12", "48h12", tagCustom48h12_create, tagCustom48h12_destroy},
};

const FamilyFunctions& Find(const std::string& name) {
  for (const FamilyFunctions& f : kFamilies) {
    if (name == f.name || name == f.short_name) return f;
  }
  std::string known;
  for (const FamilyFunctions& f : kFamilies)
    known += std::string(known.empty() ? "" : ", ") + f.name;
  throw std::invalid_argument("AprilTag family '" + name + "' unknown; use one of " + known +
                              " (or the short form, e.g. 36h11)");
}

}  // namespace

std::string CanonicalAprilTagFamilyName(const std::string& name) { return Find(name).name; }

AprilTagFamilyPtr CreateAprilTagFamily(const std::string& name) {
  const FamilyFunctions& f = Find(name);
  return AprilTagFamilyPtr(f.create(), f.destroy);
}

std::vector<std::string> AprilTagFamilyNames() {
  std::vector<std::string> names;
  for (const FamilyFunctions& f : kFamilies) names.emplace_back(f.name);
  return names;
}

}  // namespace aperture::perception
