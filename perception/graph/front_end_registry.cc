#include "perception/graph/front_end_registry.h"

#include <set>
#include <sstream>
#include <stdexcept>

#include "config/usage_error.h"

namespace aperture::perception {

void FrontEndRegistry::Register(const std::string& name, std::string description,
                                FrontEndFactory factory) {
  if (name.empty()) throw std::invalid_argument("FrontEndRegistry: empty front-end name");
  if (!factory) {
    throw std::invalid_argument("FrontEndRegistry: front end '" + name + "' has no factory");
  }
  if (!entries_.emplace(name, Entry{std::move(description), std::move(factory)}).second) {
    throw std::invalid_argument("FrontEndRegistry: front end '" + name + "' is registered twice");
  }
}

std::vector<std::string> FrontEndRegistry::Names() const {
  std::vector<std::string> names;
  for (const auto& [name, entry] : entries_) names.push_back(name);
  return names;
}

const FrontEndRegistry::Entry& FrontEndRegistry::Find(const std::string& name) const {
  const auto it = entries_.find(name);
  if (it == entries_.end()) {
    std::ostringstream message;
    message << "unknown front end '" << name << "'; known front ends:";
    for (const auto& [known, entry] : entries_) message << " " << known;
    throw config::UsageError(message.str());  // the name came from --frontends
  }
  return it->second;
}

const std::string& FrontEndRegistry::Description(const std::string& name) const {
  return Find(name).description;
}

const CameraCalibration& FrontEndResources::RequireCalibration(const std::string& front_end) const {
  if (!calibration) {
    // A missing option: a usage error (exit 2).
    throw config::UsageError("front end '" + front_end +
                             "' needs a camera calibration: pass --calib FILE (OpenCV, ROS "
                             "camera_info or Kalibr YAML)");
  }
  return *calibration;
}

std::unique_ptr<Node> FrontEndRegistry::Create(const std::string& name, config::ParamReader& params,
                                               const FrontEndResources& resources) const {
  std::unique_ptr<Node> node = Find(name).factory(params, resources);
  if (!node) {
    throw std::invalid_argument("FrontEndRegistry: the factory of '" + name + "' returned no node");
  }
  params.RejectUnknownKeys();
  return node;
}

std::unique_ptr<Node> FrontEndRegistry::Create(const std::string& name,
                                               const FrontEndResources& resources) const {
  config::ParamReader defaults(YAML::Node(), name + " defaults");
  return Create(name, defaults, resources);
}

FrameGraph FrontEndRegistry::BuildGraph(const std::vector<std::string>& front_ends,
                                        config::ParamReader& root,
                                        const FrontEndResources& resources) const {
  if (front_ends.empty()) {
    std::string known;
    for (const std::string& name : Names()) known += " " + name;
    throw std::invalid_argument("no front end selected; known front ends:" + known);
  }
  std::set<std::string> seen;
  std::vector<std::unique_ptr<Node>> nodes;
  for (const std::string& name : front_ends) {
    if (!seen.insert(name).second) {
      throw std::invalid_argument("front end '" + name + "' is listed twice");
    }
    config::ParamReader params = root.Section(name);
    nodes.push_back(Create(name, params, resources));
  }
  return FrameGraph(std::move(nodes));
}

FrameGraph FrontEndRegistry::BuildGraph(const std::vector<std::string>& front_ends,
                                        const FrontEndResources& resources) const {
  config::ParamReader defaults(YAML::Node(), "defaults");
  return BuildGraph(front_ends, defaults, resources);
}

std::vector<std::string> SplitFrontEndList(const std::string& comma_separated) {
  std::vector<std::string> names;
  std::stringstream stream(comma_separated);
  std::string item;
  while (std::getline(stream, item, ',')) {
    const auto first = item.find_first_not_of(" \t");
    const auto last = item.find_last_not_of(" \t");
    if (first == std::string::npos) {
      throw std::invalid_argument("front-end list '" + comma_separated +
                                  "' has an empty entry; write e.g. 'image_quality,tags'");
    }
    names.push_back(item.substr(first, last - first + 1));
  }
  // getline drops a trailing empty item ("a,"): report it too.
  if (names.empty() || comma_separated.back() == ',') {
    throw std::invalid_argument("front-end list '" + comma_separated +
                                "' has an empty entry; write e.g. 'image_quality,tags'");
  }
  return names;
}

}  // namespace aperture::perception
