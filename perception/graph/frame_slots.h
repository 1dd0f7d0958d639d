#pragma once
// The values of one frame's run through a FrameGraph: one type-erased slot per declared slot
// name, each checked against its declared type on every access.
//
// Thread safety: the set of slots is fixed at construction, so distinct slots may be read and
// written concurrently (the parallel executor does this). A slot must not be read while it is
// being written; the graph's dependency order guarantees that for nodes.
#include <any>
#include <map>
#include <string>
#include <typeindex>
#include <utility>
#include <vector>

#include "perception/graph/slot_spec.h"

namespace aperture::perception {

class FrameSlots {
 public:
  // One empty slot per spec. Throws std::invalid_argument on a repeated slot name.
  explicit FrameSlots(const std::vector<SlotSpec>& slots);

  // Typed access. Throws std::invalid_argument naming the slot if it does not exist, if T is not
  // its declared type, or (Get) if it holds no value yet. `accessor` (e.g. a node name) prefixes
  // messages.
  template <typename T>
  const T& Get(const std::string& name, const std::string& accessor = "FrameSlots") const {
    return *std::any_cast<T>(&Read(name, typeid(T), accessor));
  }
  template <typename T>
  void Set(const std::string& name, T value, const std::string& accessor = "FrameSlots") {
    Write(name, typeid(T), accessor) = std::move(value);
  }

  bool Contains(const std::string& name) const { return slots_.count(name) > 0; }
  bool HasValue(const std::string& name) const;
  // Drops all values, keeps the slots (reuse between frames).
  void ClearValues();
  std::vector<std::string> Names() const;

 private:
  struct Slot {
    std::type_index type;
    std::any value;
  };
  const Slot& Find(const std::string& name, const std::string& accessor) const;
  // Checked access to a slot's storage: existence and type (and, for Read, a value present).
  const std::any& Read(const std::string& name, std::type_index type,
                       const std::string& accessor) const;
  std::any& Write(const std::string& name, std::type_index type, const std::string& accessor);

  std::map<std::string, Slot> slots_;
};

}  // namespace aperture::perception
