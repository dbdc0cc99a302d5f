// SPDX-License-Identifier: MIT
#include "machine_for_link.hpp"

#include <nlohmann/json.hpp>

#include <curvestep/host/job.hpp>

namespace curvestep::host {

MachineFile load_machine_for_link(const std::string& path) {
  const std::string text = read_text_file(path);
  const auto root = nlohmann::json::parse(text, nullptr, false, true);
  if (root.is_object() && root.contains("gpio")) {
    auto planning = root;
    planning.erase("gpio");
    return parse_machine_file(planning.dump(2), path);
  }
  return load_machine_file(path);
}

}  // namespace curvestep::host
