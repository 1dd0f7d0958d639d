#include "perception/graph/frame_slots.h"

#include <sstream>
#include <stdexcept>

namespace aperture::perception {

FrameSlots::FrameSlots(const std::vector<SlotSpec>& slots) {
  for (const SlotSpec& spec : slots) {
    if (!slots_.emplace(spec.name, Slot{spec.type, {}}).second) {
      throw std::invalid_argument("FrameSlots: slot '" + spec.name + "' is declared twice");
    }
  }
}

bool FrameSlots::HasValue(const std::string& name) const {
  const auto it = slots_.find(name);
  return it != slots_.end() && it->second.value.has_value();
}

void FrameSlots::ClearValues() {
  for (auto& [name, slot] : slots_) slot.value.reset();
}

std::vector<std::string> FrameSlots::Names() const {
  std::vector<std::string> names;
  for (const auto& [name, slot] : slots_) names.push_back(name);
  return names;
}

const FrameSlots::Slot& FrameSlots::Find(const std::string& name,
                                         const std::string& accessor) const {
  const auto it = slots_.find(name);
  if (it == slots_.end()) {
    std::ostringstream message;
    message << accessor << ": no slot '" << name << "' in this graph; slots are:";
    for (const auto& [known, slot] : slots_) message << " '" << known << "'";
    throw std::invalid_argument(message.str());
  }
  return it->second;
}

const std::any& FrameSlots::Read(const std::string& name, std::type_index type,
                                 const std::string& accessor) const {
  const Slot& slot = Find(name, accessor);
  if (slot.type != type) {
    throw std::invalid_argument(accessor + ": slot '" + name + "' holds " + TypeName(slot.type) +
                                ", not " + TypeName(type));
  }
  if (!slot.value.has_value()) {
    throw std::invalid_argument(accessor + ": slot '" + name +
                                "' has no value (its producer did not Set it this frame)");
  }
  return slot.value;
}

std::any& FrameSlots::Write(const std::string& name, std::type_index type,
                            const std::string& accessor) {
  Slot& slot = const_cast<Slot&>(Find(name, accessor));
  if (slot.type != type) {
    throw std::invalid_argument(accessor + ": slot '" + name + "' holds " + TypeName(slot.type) +
                                ", cannot Set a " + TypeName(type));
  }
  return slot.value;
}

}  // namespace aperture::perception
