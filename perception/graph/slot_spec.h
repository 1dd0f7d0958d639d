#pragma once
// A named, typed slot of the frame graph: what a node reads or writes. Slot values are stored
// type-erased (std::any) but every access is checked against the declared type.
#include <string>
#include <typeindex>
#include <typeinfo>

namespace aperture::perception {

// The root slot every graph provides: the source Frame (perception/sensor_data.h).
inline constexpr const char* kFrameSlot = "frame";

struct SlotSpec {
  std::string name;
  std::type_index type = typeid(void);
};

// MakeSlot<cv::Mat>("edges") declares a slot "edges" holding a cv::Mat.
template <typename T>
SlotSpec MakeSlot(std::string name) {
  return SlotSpec{std::move(name), std::type_index(typeid(T))};
}

// Human-readable (demangled) name of a type for error messages, e.g. "cv::Mat".
std::string TypeName(std::type_index type);

}  // namespace aperture::perception
