// SPDX-License-Identifier: MIT
// curvestep: evaluate, sample, simulate and stream motion paths.
#include <algorithm>
#include <exception>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include <curvestep/host/printable.hpp>

#include "command_registry.hpp"

int main(int argc, char** argv) {
  CLI::App app{"curvestep: allocation-free Bezier/B-spline motion paths for CNC and plotter controllers"};
  app.require_subcommand(1);
  // One line on failure: the cause, no "Run with --help" hint.
  app.failure_message(
      [](const CLI::App*, const CLI::Error& e) { return "curvestep: " + curvestep::host::printable(e.what()) + "\n"; });
  auto commands = curvestep::host::command_registry();
  std::sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.order < b.order; });
  for (const auto& command : commands) command.add(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "curvestep: " << curvestep::host::printable(e.what()) << "\n";
    return 1;
  }
  return 0;
}
