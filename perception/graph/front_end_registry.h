#pragma once
// Front ends by name, so `aperture run --frontends a,b` can compose a FrameGraph. A front end is a
// factory making one Node from its parameters (key -> value strings; the factory reads them with
// ParamReader and rejects unknown keys).
//
// No self-registration (static initializers in a static library get dropped by the linker): the
// application owns a registry and calls RegisterBuiltinFrontEnds(registry) (builtin_front_ends.h).
//
//   FrontEndRegistry registry;
//   RegisterBuiltinFrontEnds(registry);
//   FrameGraph graph = registry.BuildGraph(SplitFrontEndList("image_quality,tags"), params);
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "perception/graph/frame_graph.h"
#include "perception/graph/node.h"
#include "perception/graph/param_reader.h"

namespace aperture::perception {

using FrontEndFactory = std::function<std::unique_ptr<Node>(const NodeParams& params)>;

class FrontEndRegistry {
 public:
  // Throws std::invalid_argument on an empty or already registered name or an empty factory.
  void Register(const std::string& name, std::string description, FrontEndFactory factory);

  bool Contains(const std::string& name) const { return entries_.count(name) > 0; }
  std::vector<std::string> Names() const;  // sorted
  const std::string& Description(const std::string& name) const;

  // Throws std::invalid_argument for an unknown name (listing the known ones) and passes on the
  // factory's errors (bad or unknown parameters).
  std::unique_ptr<Node> Create(const std::string& name, const NodeParams& params = {}) const;

  // One node per front end, in the given order; params_by_front_end[name] configures front end
  // `name` (entries for front ends not listed are ignored, so one config can serve many runs).
  // Throws std::invalid_argument on an empty list, a repeated or unknown name, bad parameters,
  // or an invalid graph (e.g. a front end that needs another one not listed).
  FrameGraph BuildGraph(const std::vector<std::string>& front_ends,
                        const std::map<std::string, NodeParams>& params_by_front_end = {}) const;

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
