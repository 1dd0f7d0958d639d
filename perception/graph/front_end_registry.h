#pragma once
// Front ends by name, so `aperture run --frontends a,b` can compose a FrameGraph. A front end is a
// factory making one Node from its parameters: the config section named after the front end
// (`--set image_quality.histogram_bins=32`), read strictly with config::ParamReader.
//
// No self-registration (static initializers in a static library get dropped by the linker): the
// application owns a registry and calls RegisterBuiltinFrontEnds(registry) (builtin_front_ends.h).
//
//   FrontEndRegistry registry;
//   RegisterBuiltinFrontEnds(registry);
//   config::ParamReader root = config_tree.Reader();
//   FrameGraph graph = registry.BuildGraph(SplitFrontEndList("image_quality,tags"), root);
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/param_reader.h"
#include "perception/camera/calibration_io.h"
#include "perception/graph/frame_graph.h"
#include "perception/graph/node.h"
#include "perception/tags/tag_detector_registry.h"

namespace aperture::perception {

// What a run offers every front end besides its parameters.
struct FrontEndResources {
  // The camera calibration (`aperture run --calib`), when one was given.
  std::optional<CameraCalibration> calibration;
  // The run's output folder, where a front end may write its own files (Node::Finish); empty:
  // write none (tests, SITL).
  std::string output_directory;
  // Tag detectors by name for the `apriltag` front end; the application adds those of higher
  // layers (servo/'s ViSP detector).
  TagDetectorRegistry tag_detectors = TagDetectorRegistry::WithBuiltins();

  // The calibration, or std::invalid_argument telling the user that `front_end` needs --calib.
  const CameraCalibration& RequireCalibration(const std::string& front_end) const;
};

// Reads its parameters from `params` (config::ParamReader::Read...); the registry rejects the
// keys it did not read.
using FrontEndFactory = std::function<std::unique_ptr<Node>(config::ParamReader& params,
                                                            const FrontEndResources& resources)>;

class FrontEndRegistry {
 public:
  // Throws std::invalid_argument on an empty or already registered name or an empty factory.
  void Register(const std::string& name, std::string description, FrontEndFactory factory);

  bool Contains(const std::string& name) const { return entries_.count(name) > 0; }
  std::vector<std::string> Names() const;  // sorted
  const std::string& Description(const std::string& name) const;

  // Throws std::invalid_argument for an unknown name (listing the known ones), passes on the
  // factory's errors (bad parameters) and rejects parameters the factory did not read.
  std::unique_ptr<Node> Create(const std::string& name, config::ParamReader& params,
                               const FrontEndResources& resources = {}) const;
  // With all parameters at their defaults.
  std::unique_ptr<Node> Create(const std::string& name,
                               const FrontEndResources& resources = {}) const;

  // One node per front end, in the given order; section `name` of `root` configures front end
  // `name` (root.Section(name), so the sections read are marked known in `root`; the caller
  // decides whether other sections are errors with root.RejectUnknownKeys()).
  // Throws std::invalid_argument on an empty list, a repeated or unknown name, bad parameters,
  // or an invalid graph (e.g. a front end that needs another one not listed).
  FrameGraph BuildGraph(const std::vector<std::string>& front_ends, config::ParamReader& root,
                        const FrontEndResources& resources = {}) const;
  // With all parameters at their defaults.
  FrameGraph BuildGraph(const std::vector<std::string>& front_ends,
                        const FrontEndResources& resources = {}) const;

 private:
  struct Entry {
    std::string description;
    FrontEndFactory factory;
  };
  const Entry& Find(const std::string& name) const;

  std::map<std::string, Entry> entries_;
};

// "a, b,c" -> {"a", "b", "c"} (whitespace trimmed). Throws std::invalid_argument on an empty item.
std::vector<std::string> SplitFrontEndList(const std::string& comma_separated);

}  // namespace aperture::perception
