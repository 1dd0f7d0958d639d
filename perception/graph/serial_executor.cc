#include "perception/graph/serial_executor.h"

namespace aperture::perception {

void SerialExecutor::RunNodes(FrameSlots& slots) {
  for (std::size_t index : graph_.topological_order()) RunNode(index, slots);
}

}  // namespace aperture::perception
