#pragma once
// A node's typed view of one frame's slots (FrameSlots), restricted to the slots the node
// declared: Get reads a declared input (or one of its own outputs), Set writes a declared output.
// Anything else, a type mismatch, or reading an unset slot throws std::invalid_argument naming
// the node and the slot. Nodes receive a mutable context in Run and a const one in Metrics and
// DrawOverlay (read only).
#include <string>
#include <utility>
#include <vector>

#include "perception/graph/frame_slots.h"
#include "perception/graph/slot_spec.h"

namespace aperture::perception {

// What a node reads and writes, as cached by the FrameGraph when it is built.
struct NodeDeclaration {
  std::string name;
  std::vector<SlotSpec> inputs;
  std::vector<SlotSpec> outputs;
};

class NodeContext {
 public:
  // `slots` and `declaration` must outlive the context (FrameGraph::ContextFor builds these).
  NodeContext(FrameSlots& slots, const NodeDeclaration& declaration)
      : slots_(&slots), declaration_(&declaration) {}

  template <typename T>
  const T& Get(const std::string& name) const {
    CheckDeclared(name, /*for_write=*/false);
    return slots_->Get<T>(name, declaration_->name);
  }
  template <typename T>
  void Set(const std::string& name, T value) {
    CheckDeclared(name, /*for_write=*/true);
    slots_->Set<T>(name, std::move(value), declaration_->name);
  }

  const std::string& node_name() const { return declaration_->name; }

 private:
  void CheckDeclared(const std::string& name, bool for_write) const;

  FrameSlots* slots_;
  const NodeDeclaration* declaration_;
};

}  // namespace aperture::perception
