// SPDX-License-Identifier: MIT
// Registration of the curvestep subcommands with the CLI11 application.
#pragma once

#include <CLI/CLI.hpp>

namespace curvestep::host {

/// Adds `curvestep demo`.
void add_demo_command(CLI::App& app);

}  // namespace curvestep::host
