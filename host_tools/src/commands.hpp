// SPDX-License-Identifier: MIT
// Registration of the curvestep subcommands with the CLI11 application.
#pragma once

#include <CLI/CLI.hpp>

namespace curvestep::host {

/// Adds `curvestep demo`.
void add_demo_command(CLI::App& app);
/// Adds `curvestep eval` (exact points of one job segment).
void add_eval_command(CLI::App& app);
/// Adds `curvestep sample` (a job flattened within a tolerance).
void add_sample_command(CLI::App& app);
/// Adds `curvestep sim` (replay a job through the motion controller).
void add_sim_command(CLI::App& app);

}  // namespace curvestep::host
