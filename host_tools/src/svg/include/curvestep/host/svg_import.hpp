// SPDX-License-Identifier: MIT
// SVG import: a drawing's paths and shapes as a host Job whose curves stay curves.
//
// Every path command (M L H V C S Q T A Z, absolute and relative), the basic shapes and nested
// groups with transforms are mapped through one affine map per element onto machine millimetres
// (docs/svg_import.md): lines stay lines, quadratic and cubic Béziers keep their control points
// (Béziers are affine invariant), and elliptical arcs become rational quadratic Béziers of at most
// 90° of the underlying circle each, which represent an ellipse exactly. Control points, weights
// and the feed are rounded to the nearest Q16.16 value like job files (the wire's format, so the
// simulator sees what a device receives). Subpaths are joined by rapid moves. Top-level Inkscape
// layers are drawn one after the other in document order (the optimiser reorders within a layer),
// with a LayerChange event (a pen change) before each layer after the first.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/load_error.hpp>

namespace curvestep::host {

/// How a drawing becomes a job.
/// The most elements all <use> references of one file may expand to together (docs/robustness.md).
inline constexpr std::size_t max_svg_expanded_elements = 100000;

struct SvgOptions {
  bool optimize = false;             ///< reorder subpaths (greedy nearest neighbour, open ones may be reversed)
  MachinePoint start{};              ///< where the machine stands before the job, mm (the first rapid starts here)
  double feed_mm_per_s = 0;          ///< feed of the drawing segments (rounded to Q16.16), 0 for the machine default
  /// Refuse a file with malformed path data or points (LoadError). Otherwise SVG's error rule: a
  /// path is drawn up to its first error, a points list up to its error or odd last number, and
  /// SvgImport::warnings names file, line, element, attribute and character.
  bool strict = false;
  /// Inkscape layers to draw, by label (empty: all, and the content outside layers). LoadError for
  /// a label no top-level layer has, listing the layers there are.
  std::vector<std::string> layers;
};

/// A job made from a drawing, with what the import did.
struct SvgImport {
  Job job;                              ///< the path: rapids between subpaths, curves as (rational) Béziers
  std::size_t subpath_count = 0;        ///< drawn subpaths (each one pen-down stretch)
  std::size_t reversed_count = 0;       ///< subpaths the optimiser drew backwards
  double travel_document_mm = 0;        ///< rapid travel in document order
  double travel_mm = 0;                 ///< rapid travel of `job`
  std::vector<std::string> layers;      ///< labels of the layers drawn, in order ("(outside layers)" for the rest); a LayerChange event between each two
  std::vector<std::string> warnings;    ///< elements not drawn, data drawn up to an error ("file:line: <path> "d": at character 9: ...")
  std::optional<double> page_width_mm;  ///< the document's page (the root's width and height), where they give one
  std::optional<double> page_height_mm;
  /// Rapid travel the optimiser saved, mm.
  [[nodiscard]] double travel_saved_mm() const noexcept { return travel_document_mm - travel_mm; }
};

/// Imports an SVG file. Throws LoadError (file, line, element, attribute, cause) or
/// std::runtime_error if the file cannot be read.
[[nodiscard]] SvgImport load_svg(const std::filesystem::path& path, const SvgOptions& options = {});

/// Imports SVG text; `name` is the file name used in messages.
[[nodiscard]] SvgImport parse_svg(std::string_view text, std::string name, const SvgOptions& options = {});

/// load_svg(...).job.
[[nodiscard]] Job import_svg(const std::filesystem::path& path, const SvgOptions& options = {});

/// parse_svg(...).job.
[[nodiscard]] Job parse_svg_job(std::string_view text, std::string name, const SvgOptions& options = {});

}  // namespace curvestep::host
