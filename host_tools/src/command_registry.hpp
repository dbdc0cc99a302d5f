// SPDX-License-Identifier: MIT
// Self-registering subcommands: each *_command.cpp adds itself, so no central list needs editing.
#pragma once

#include <functional>
#include <vector>

#include <CLI/CLI.hpp>

namespace curvestep::host {

/// Adds one subcommand (its options and callback) to the application.
using CommandAdder = void (*)(CLI::App& app);

/// Every registered subcommand with its position in `curvestep --help`.
struct RegisteredCommand {
  int order = 0;
  CommandAdder add = nullptr;
};

/// The registry (filled during static initialisation, read by main).
std::vector<RegisteredCommand>& command_registry();

/// `const RegisterCommand registered{30, add_sim_command};` at namespace scope in a *_command.cpp.
struct RegisterCommand {
  RegisterCommand(int order, CommandAdder add) { command_registry().push_back({order, add}); }
};

}  // namespace curvestep::host
