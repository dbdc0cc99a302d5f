// SPDX-License-Identifier: MIT
#include "command_registry.hpp"

namespace curvestep::host {

std::vector<RegisteredCommand>& command_registry() {
  static std::vector<RegisteredCommand> registry;
  return registry;
}

}  // namespace curvestep::host
