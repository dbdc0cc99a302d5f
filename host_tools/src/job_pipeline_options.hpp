// SPDX-License-Identifier: MIT
// The command-line options of the job pipeline (job_pipeline.hpp), the same on every command that
// moves a machine: sim, plot, stream, gpio.
#pragma once

#include <CLI/CLI.hpp>

#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/machine_file.hpp>

namespace curvestep::host {

/// Adds --optimize, --strict, --blend-tolerance and --strict-step-rate to `command`, filling `options`.
inline void add_job_pipeline_options(CLI::App* command, JobPipelineOptions& options) {
  command->add_flag("--optimize", options.optimize, "SVG: order subpaths to shorten pen-up travel");
  command->add_flag("--strict", options.strict_svg,
                    "SVG: refuse a file with malformed path data or points (by default SVG's rule: drawn up to the error, "
                    "with a warning naming file:line and character)");
  command->add_option("--blend-tolerance", options.blend_tolerance_mm,
                      "Path smoothing tolerance in mm (corner blends and line-run fits; 0 = off), overriding the machine "
                      "file's \"blend_tolerance\" (docs/motion.md, \"Path smoothing\")")
      ->check(CLI::Range(0.0, max_blend_tolerance_mm));
  command->add_flag("--strict-step-rate", options.strict_step_rate,
                    "Refuse a job whose axis speed needs more than max_step_rate instead of planning that axis slower");
}

}  // namespace curvestep::host
