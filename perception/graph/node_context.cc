#include "perception/graph/node_context.h"

#include <algorithm>
#include <stdexcept>

namespace aperture::perception {
namespace {

bool Declares(const std::vector<SlotSpec>& slots, const std::string& name) {
  return std::any_of(slots.begin(), slots.end(),
                     [&name](const SlotSpec& slot) { return slot.name == name; });
}

}  // namespace

void NodeContext::CheckDeclared(const std::string& name, bool for_write) const {
  if (for_write) {
    if (!Declares(declaration_->outputs, name)) {
      throw std::invalid_argument("node '" + declaration_->name + "' sets slot '" + name +
                                  "' but does not declare it in Outputs()");
    }
  } else if (!Declares(declaration_->inputs, name) && !Declares(declaration_->outputs, name)) {
    throw std::invalid_argument("node '" + declaration_->name + "' reads slot '" + name +
                                "' but declares it neither in Inputs() nor in Outputs()");
  }
}

}  // namespace aperture::perception
