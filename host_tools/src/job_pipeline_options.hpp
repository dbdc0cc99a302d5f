// SPDX-License-Identifier: MIT
// The command-line options of the job pipeline (job_pipeline.hpp), the same on every command that
// moves a machine: sim, plot, stream, gpio, demo.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/machine_file.hpp>

namespace curvestep::host {

/// Adds --subroutine-path (repeatable) to `command`, filling `folders`.
inline void add_subroutine_path_option(CLI::App* command, std::vector<std::string>& folders) {
  command->add_option("--subroutine-path", folders,
                      "G-code: a folder of subroutine files (o<name> call reads name.ngc), searched after the program's own "
                      "folder; repeat it for more, searched in order (LinuxCNC's SUBROUTINE_PATH, docs/gcode.md)")
      ->check(CLI::ExistingDirectory);
}

/// Adds --optimize, --strict, --layers, the page options (--page, --landscape, --center, --fit, --margin,
/// --rotate), --blend-tolerance, --strict-step-rate and --subroutine-path to `command`, filling `options`.
inline void add_job_pipeline_options(CLI::App* command, JobPipelineOptions& options) {
  command->add_flag("--optimize", options.optimize, "SVG: order subpaths to shorten pen-up travel");
  command->add_flag("--strict", options.strict_svg,
                    "SVG: refuse a file with malformed path data or points (by default SVG's rule: drawn up to the error, "
                    "with a warning naming file:line and character)");
  command->add_option("--layers", options.layers,
                      "SVG: draw only these Inkscape layers (labels, comma-separated), in document order")
      ->delimiter(',');
  command->add_option("--page", options.page,
                      "SVG: the page (a5, a4, a3, letter, legal, tabloid or WxH with mm/cm/in, e.g. 210x297mm); the drawing "
                      "must fit it before anything moves");
  command->add_flag("--landscape", options.landscape, "SVG: turn the page so its longer side runs along x");
  command->add_flag("--center", options.center, "SVG: centre the drawing on the page");
  command->add_flag("--fit", options.fit, "SVG: scale the drawing uniformly to the page minus --margin, centred");
  command->add_option("--margin", options.margin, "SVG: margin kept free by --fit (mm, or with mm/cm/in)");
  command->add_option("--rotate", options.rotate_deg, "SVG: rotate the drawing clockwise about its centre by 90, 180 or 270 degrees")
      ->check(CLI::IsMember({0, 90, 180, 270}));
  command->add_option("--blend-tolerance", options.blend_tolerance_mm,
                      "Path smoothing tolerance in mm (corner blends and line-run fits; 0 = off), overriding the machine "
                      "file's \"blend_tolerance\" (docs/motion.md, \"Path smoothing\")")
      ->check(CLI::Range(0.0, max_blend_tolerance_mm));
  command->add_flag("--strict-step-rate", options.strict_step_rate,
                    "Refuse a job whose axis speed needs more than max_step_rate instead of planning that axis slower");
  add_subroutine_path_option(command, options.subroutine_path);
}

}  // namespace curvestep::host
