// SPDX-License-Identifier: MIT
#include <curvestep/host/job_file.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include <curvestep/host/gcode_import.hpp>
#include <curvestep/host/parameter_speed.hpp>
#include <curvestep/host/svg_import.hpp>
#include <curvestep/host/swept_extent.hpp>

namespace curvestep::host {

namespace {

/// The file's extension in lower case, after checking that the SVG-only options are not given to another format.
std::string checked_extension(const std::filesystem::path& path, const JobFileOptions& options) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const bool svg_file = extension == ".svg";
  if (!svg_file && options.page.active()) {
    throw std::invalid_argument(path.string() + ": --page, --center, --fit and --rotate apply to SVG drawings only");
  }
  if (!svg_file && !options.layers.empty()) throw std::invalid_argument(path.string() + ": --layers applies to SVG drawings only");
  return extension;
}

/// The extensions CAM posts, senders and laser tools give G-code files (LinuxCNC's .ngc, Mach3's
/// .tap, grbl senders' .nc .gc .gcode, .gco, .g and .cnc).
constexpr std::array<std::string_view, 8> gcode_extensions{".ngc", ".nc", ".gcode", ".tap", ".gc", ".gco", ".g", ".cnc"};

bool is_gcode(const std::string& extension) {
  return std::find(gcode_extensions.begin(), gcode_extensions.end(), extension) != gcode_extensions.end();
}

/// The G-code extensions joined by `separator`.
std::string gcode_extension_list(std::string_view separator) {
  std::string list;
  for (const auto extension : gcode_extensions) list += (list.empty() ? "" : std::string(separator)) + std::string(extension);
  return list;
}

/// ".json, .ngc, ..., .svg": every format load_job_file reads.
std::string understood_extensions() { return ".json, " + gcode_extension_list(", ") + ", .svg"; }

/// Without --page the drawing is plotted where the document puts it: a note when that is outside
/// the document's own page (a renderer clips it there; on paper it runs off the sheet).
void note_off_document_page(const SvgImport& imported, const std::filesystem::path& path, std::vector<std::string>& notes) {
  if (!imported.page_width_mm || !imported.page_height_mm) return;
  const auto extent = drawing_extent(imported.job);
  if (!extent) return;
  const std::string overflow = page_overflow(extent->first, extent->second, *imported.page_width_mm, *imported.page_height_mm);
  if (overflow.empty()) return;
  std::ostringstream line;
  line << path.string() << ": the drawing reaches " << overflow << " (the document's own page, " << *imported.page_width_mm << " x "
       << *imported.page_height_mm << " mm): a viewer clips it there, the pen draws it off the sheet; --page SIZE --fit (or --center) "
       << "lays it out on a page";
  notes.push_back(line.str());
}

Job load_by_extension(const std::filesystem::path& path, const JobFileOptions& options, std::vector<std::string>* notes) {
  const std::string extension = checked_extension(path, options);
  if (extension == ".json") return load_job(path);
  if (is_gcode(extension)) return import_gcode(path, options.gcode);
  if (extension == ".svg") {
    SvgOptions svg;
    svg.optimize = options.optimize;
    svg.strict = options.strict_svg;
    svg.layers = options.layers;
    SvgImport imported = load_svg(path, svg);
    if (notes != nullptr) {
      for (const auto& warning : imported.warnings) notes->push_back(warning);  // each names the file and line
      if (imported.layers.size() > 1) {
        std::string line = "layers drawn in order, a pen change (layer change event) before each after the first:";
        for (const auto& layer : imported.layers) line += " \"" + layer + "\"";
        notes->push_back(line);
      }
      if (options.optimize) {
        std::ostringstream line;
        line << "optimised pen-up travel: " << imported.travel_document_mm << " mm -> " << imported.travel_mm << " mm (saved "
             << imported.travel_saved_mm() << " mm, " << imported.reversed_count << " subpaths reversed)";
        notes->push_back(line.str());
      }
    }
    if (options.page.active()) {
      // Before anything moves: the drawing placed on the page and checked against it.
      const PageLayoutReport report = lay_out_on_page(imported.job, options.page, svg.start);
      if (notes != nullptr) notes->push_back(report.note);
    } else if (notes != nullptr) {
      note_off_document_page(imported, path, *notes);
    }
    return std::move(imported.job);
  }
  throw std::runtime_error(path.string() + ": unknown job format '" + extension + "' (understood: " + understood_extensions() + ")");
}

}  // namespace

std::string job_file_help() { return "Job file: .json, G-code (" + gcode_extension_list(" ") + ") or .svg"; }

Job load_job_file(const std::filesystem::path& path, const JobFileOptions& options, std::vector<std::string>* notes) {
  Job job = load_by_extension(path, options, notes);
  // Every format: no job starts that the controller would refuse halfway or could not follow.
  check_swept_extent(job);
  check_parameter_speed(job);
  return job;
}

Job load_job_file(const std::filesystem::path& path, const JobFileOptions& options, std::vector<std::string>* notes, JobSink& sink) {
  if (is_gcode(checked_extension(path, options))) return import_gcode(path, options.gcode, sink);  // checked as it streams
  return feed_job(load_job_file(path, options, notes), sink);
}

}  // namespace curvestep::host
