#include "perception/graph/frame_graph.h"

#include <algorithm>
#include <functional>
#include <opencv2/imgproc.hpp>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace aperture::perception {
namespace {

constexpr const char* kSourceName = "<source>";

struct Producer {
  std::string node_name;  // kSourceName for the frame
  std::type_index type;
  std::size_t index;  // node index; unused for the source
  bool is_source;
};

// Returns a cycle among the nodes not ordered by Kahn's algorithm, as node indices with the first
// repeated at the end (a -> b -> a).
std::vector<std::size_t> FindCycle(const std::vector<std::vector<std::size_t>>& dependencies,
                                   const std::vector<bool>& ordered) {
  const std::size_t n = dependencies.size();
  enum class Mark { kNew, kOnStack, kDone };
  std::vector<Mark> marks(n, Mark::kNew);
  std::vector<std::size_t> stack;
  std::vector<std::size_t> cycle;
  std::function<bool(std::size_t)> visit = [&](std::size_t node) {
    marks[node] = Mark::kOnStack;
    stack.push_back(node);
    for (std::size_t dependency : dependencies[node]) {
      if (marks[dependency] == Mark::kOnStack) {
        const auto start = std::find(stack.begin(), stack.end(), dependency);
        // `stack` runs consumer -> producer; report producer -> consumer.
        cycle.assign(start, stack.end());
        std::reverse(cycle.begin(), cycle.end());
        cycle.push_back(cycle.front());
        return true;
      }
      if (marks[dependency] == Mark::kNew && visit(dependency)) return true;
    }
    stack.pop_back();
    marks[node] = Mark::kDone;
    return false;
  };
  for (std::size_t node = 0; node < n; ++node) {
    if (!ordered[node] && marks[node] == Mark::kNew && visit(node)) break;
  }
  return cycle;
}

}  // namespace

FrameGraph::FrameGraph(std::vector<std::unique_ptr<Node>> nodes) : nodes_(std::move(nodes)) {
  const std::size_t n = nodes_.size();
  std::map<std::string, std::size_t> node_by_name;
  for (std::size_t i = 0; i < n; ++i) {
    if (!nodes_[i])
      throw std::invalid_argument("FrameGraph: node #" + std::to_string(i) + " is null");
    NodeDeclaration declaration{nodes_[i]->Name(), nodes_[i]->Inputs(), nodes_[i]->Outputs()};
    if (declaration.name.empty()) {
      throw std::invalid_argument("FrameGraph: node #" + std::to_string(i) + " has an empty name");
    }
    const auto [it, inserted] = node_by_name.emplace(declaration.name, i);
    if (!inserted) {
      throw std::invalid_argument("FrameGraph: two nodes are named '" + declaration.name + "' (#" +
                                  std::to_string(it->second) + " and #" + std::to_string(i) +
                                  "); node names must be unique");
    }
    declarations_.push_back(std::move(declaration));
  }

  // Producers: the source produces "frame", each node its outputs.
  std::map<std::string, Producer> producers;
  producers.emplace(kFrameSlot, Producer{kSourceName, typeid(Frame), 0, true});
  slots_.push_back(MakeSlot<Frame>(kFrameSlot));
  for (std::size_t i = 0; i < n; ++i) {
    for (const SlotSpec& output : declarations_[i].outputs) {
      if (output.name.empty()) {
        throw std::invalid_argument("FrameGraph: node '" + declarations_[i].name +
                                    "' declares an output with an empty name");
      }
      const auto [it, inserted] =
          producers.emplace(output.name, Producer{declarations_[i].name, output.type, i, false});
      if (!inserted) {
        throw std::invalid_argument("FrameGraph: slot '" + output.name + "' has two producers: '" +
                                    it->second.node_name + "' and '" + declarations_[i].name +
                                    "'; rename one output");
      }
      slots_.push_back(output);
    }
  }

  // Consumers: every input needs a producer of the same type.
  dependencies_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const NodeDeclaration& consumer = declarations_[i];
    for (const SlotSpec& input : consumer.inputs) {
      const auto it = producers.find(input.name);
      if (it == producers.end()) {
        std::ostringstream message;
        message << "FrameGraph: node '" << consumer.name << "' reads slot '" << input.name << "' ("
                << TypeName(input.type)
                << ") but no node produces it; add its front end or fix the name. Produced slots:";
        for (const auto& [name, producer] : producers) {
          message << " '" << name << "' (by '" << producer.node_name << "')";
        }
        throw std::invalid_argument(message.str());
      }
      const Producer& producer = it->second;
      if (producer.type != input.type) {
        throw std::invalid_argument("FrameGraph: type mismatch on slot '" + input.name +
                                    "': node '" + producer.node_name + "' produces " +
                                    TypeName(producer.type) + " but node '" + consumer.name +
                                    "' reads " + TypeName(input.type));
      }
      if (!producer.is_source) dependencies_[i].push_back(producer.index);
    }
    std::sort(dependencies_[i].begin(), dependencies_[i].end());
    dependencies_[i].erase(std::unique(dependencies_[i].begin(), dependencies_[i].end()),
                           dependencies_[i].end());
  }

  // Kahn's algorithm, always taking the lowest ready index: a stable topological order.
  std::vector<std::vector<std::size_t>> consumers(n);
  std::vector<std::size_t> pending(n);
  for (std::size_t i = 0; i < n; ++i) {
    pending[i] = dependencies_[i].size();
    for (std::size_t dependency : dependencies_[i]) consumers[dependency].push_back(i);
  }
  std::priority_queue<std::size_t, std::vector<std::size_t>, std::greater<>> ready;
  for (std::size_t i = 0; i < n; ++i) {
    if (pending[i] == 0) ready.push(i);
  }
  std::vector<bool> ordered(n, false);
  while (!ready.empty()) {
    const std::size_t node = ready.top();
    ready.pop();
    topological_order_.push_back(node);
    ordered[node] = true;
    for (std::size_t consumer : consumers[node]) {
      if (--pending[consumer] == 0) ready.push(consumer);
    }
  }
  if (topological_order_.size() != n) {
    std::string path;
    for (std::size_t node : FindCycle(dependencies_, ordered)) {
      path += (path.empty() ? "'" : " -> '") + declarations_[node].name + "'";
    }
    throw std::invalid_argument("FrameGraph: the nodes form a cycle: " + path +
                                " (each arrow: an output read by the next node)");
  }
}

std::vector<std::string> FrameGraph::TopologicalNames() const {
  std::vector<std::string> names;
  for (std::size_t index : topological_order_) names.push_back(declarations_[index].name);
  return names;
}

FrameSlots FrameGraph::MakeSlots(const Frame& frame) const {
  FrameSlots slots(slots_);
  slots.Set<Frame>(kFrameSlot, frame);
  return slots;
}

void FrameGraph::ResetSlots(const Frame& frame, FrameSlots& slots) const {
  slots.ClearValues();
  slots.Set<Frame>(kFrameSlot, frame);
}

NodeContext FrameGraph::ContextFor(std::size_t index, FrameSlots& slots) const {
  return NodeContext(slots, declarations_.at(index));
}

std::map<std::string, double> FrameGraph::CollectMetrics(const FrameSlots& slots) const {
  std::map<std::string, double> metrics;
  for (std::size_t index : topological_order_) {
    // Metrics receives a const context: it cannot Set, so the const_cast never writes.
    const NodeContext context(const_cast<FrameSlots&>(slots), declarations_[index]);
    for (const auto& [key, value] : nodes_[index]->Metrics(context)) {
      metrics[declarations_[index].name + "." + key] = value;
    }
  }
  return metrics;
}

std::vector<PoseObservation> FrameGraph::CollectPoses(const FrameSlots& slots) const {
  std::vector<PoseObservation> poses;
  for (std::size_t index : topological_order_) {
    // Poses receives a const context: it cannot Set, so the const_cast never writes.
    const NodeContext context(const_cast<FrameSlots&>(slots), declarations_[index]);
    for (PoseObservation& pose : nodes_[index]->Poses(context)) poses.push_back(std::move(pose));
  }
  return poses;
}

std::map<std::string, std::string> FrameGraph::Finish() {
  std::map<std::string, std::string> files;
  for (std::size_t index : topological_order_) {
    for (const auto& [key, file] : nodes_[index]->Finish()) {
      files[nodes_[index]->Name() + "." + key] = file;
    }
  }
  return files;
}

void FrameGraph::DrawOverlays(const FrameSlots& slots, cv::Mat& bgr) const {
  for (std::size_t index : topological_order_) {
    // DrawOverlay receives a const context: it cannot Set, so the const_cast never writes.
    const NodeContext context(const_cast<FrameSlots&>(slots), declarations_[index]);
    nodes_[index]->DrawOverlay(context, bgr);
  }
}

cv::Mat FrameGraph::RenderOverlay(const FrameSlots& slots) const {
  const cv::Mat& image = slots.Get<Frame>(kFrameSlot).image;
  cv::Mat bgr;
  if (image.type() == CV_8UC1) {
    cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  } else if (image.type() == CV_8UC3) {
    bgr = image.clone();
  } else if (image.type() == CV_8UC4) {
    cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
  } else {
    throw std::invalid_argument(
        "FrameGraph::RenderOverlay: frame image type " +
        (image.empty() ? std::string("(empty)") : cv::typeToString(image.type())) +
        " is not CV_8UC1, CV_8UC3 or CV_8UC4");
  }
  DrawOverlays(slots, bgr);
  return bgr;
}

}  // namespace aperture::perception
