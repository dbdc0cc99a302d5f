// SPDX-License-Identifier: MIT
// G-code programs -> Job: the allocation-free parser and interpreter of lib/gcode, plus file:line.
#include <curvestep/host/gcode_import.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstddef>
#include <initializer_list>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <curvestep/core/bspline/bezier_extraction.hpp>
#include <curvestep/core/error_text.hpp>
#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/gcode.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/gcode/program_reader.hpp>
#include <curvestep/host/parameter_speed.hpp>
#include <curvestep/host/swept_extent.hpp>
#include <curvestep/host/wire_value.hpp>

#include "cutter_compensation.hpp"

namespace curvestep::host {
namespace {

/// The machine layer (lib/gcode: modal groups, offsets, motions) and the language layer
/// (host_tools/src/gcode/language: parameters, expressions, O-words).
namespace machine = ::curvestep::gcode;
namespace language = ::curvestep::host::gcode;

/// Control points one G5.2 block may hold.
constexpr std::size_t max_nurbs_points = 512;
/// Words one executed line may hold.
constexpr std::size_t machine_block_capacity = 32;
using Interpreter = machine::Interpreter<max_nurbs_points>;
using RationalSpline = Nurbs<double, motion_axes, PathSegment::max_degree, max_nurbs_points>;
constexpr double seconds_per_minute = 60.0;
/// Largest pitch error of a G18/G19 helix piece, mm, and most pieces per arc.
constexpr double helix_tolerance_mm = 1e-4;
constexpr std::size_t max_arc_pieces = 4096;
/// The interpreter checked the radii before quantisation; quantising start, end and centre (each
/// coordinate by at most 2^-17 mm) changes each radius by at most 2·√2·2^-17 mm, so their difference
/// by at most 4.4e-5 mm. make_arc gets that much slack on top of the checked difference.
constexpr double quantisation_radius_slack_mm = 1e-4;

/// The word that starts at 1-based `column` of `line` ("G5.1", "X-1.5"), or "" if none.
std::string word_at(std::string_view line, std::size_t column) {
  if (column == 0 || column > line.size()) return {};
  std::size_t position = column - 1;
  std::string word(1, machine::detail::to_upper(line[position]));
  ++position;
  while (position < line.size()) {
    const char c = line[position];
    if (machine::detail::is_digit(c) || c == '.' || c == '+' || c == '-') {
      word += c;
    } else if (!machine::detail::is_blank(c)) {
      break;
    }
    ++position;
  }
  return word;
}

/// `text` without blanks at either end.
std::string trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  return std::string(text.substr(first, text.find_last_not_of(" \t") - first + 1));
}

/// What went wrong, for the word at fault (the location names the word itself).
std::string explain(Error code, const std::string& word) {
  const bool g5_1 = word.starts_with("G5.1");
  const bool g5 = word.starts_with("G5") && !word.starts_with("G5.");
  const bool arc = word.starts_with("G2") || word.starts_with("G3");
  const bool polar = word.starts_with("@") || word.starts_with("^");
  switch (code) {
    case Error::GcodeUnsupportedWord: {
      const auto is = [&word](std::initializer_list<const char*> codes) {
        for (const char* c : codes) {
          if (word == c) return true;
        }
        return false;
      };
      if (polar) {
        return "polar coordinates (@ distance, ^ angle) work in the G17 (XY) plane only, as in LinuxCNC";
      }
      if (!word.empty() && (word[0] == 'A' || word[0] == 'B' || word[0] == 'C' || word[0] == 'U' || word[0] == 'V' || word[0] == 'W')) {
        return "rotary and parallel axes (A B C U V W) are not supported: this is a 3-axis (X Y Z) machine";
      }
      if (is({"G95"})) return "feed per revolution (G95) needs a spindle model, which this controller does not have: use G94";
      if (is({"G41", "G42", "G41.1", "G42.1"})) {
        return "cutter radius compensation works in the G17 (XY) and G18 (XZ) planes only, as in LinuxCNC (not in G19)";
      }
      if (is({"G43.2"})) return "additional tool length offsets (G43.2) are not supported: use G43 H (the machine file's tool table) or G43.1 Z";
      if (!word.empty() && (word[0] == 'X' || word[0] == 'Y')) {
        return "G43.1 takes the tool length offset along Z only: X and Y tool offsets (a lathe's) do not exist on this 3-axis machine";
      }
      if (is({"G73", "G81", "G82", "G83", "G85", "G86", "G89"})) return "canned cycles run in the G17 (XY) plane only";
      if (is({"G74", "G84"})) return "tapping cycles (G74/G84) need spindle-synchronised motion, which this controller does not have";
      if (is({"G87", "G88"})) return "back boring (G87) and manual-retract boring (G88) are not supported: use G81-G89 cycles or G0/G1";
      if (is({"G33", "G33.1", "G76"})) return "threading (spindle-synchronised motion) is not supported";
      if (is({"G7", "G8"})) return "lathe diameter/radius modes are not supported (this is a mill/plotter controller)";
      if (is({"G38.2", "G38.3", "G38.4", "G38.5"})) return "probing is not supported";
      if (!word.empty() && word[0] == 'R') {
        return "R (the coordinate system's rotation) is allowed with G10 L2 only; G10 L20 takes no R (LinuxCNC: R not allowed in G10 L20)";
      }
      if (!word.empty() && word[0] == 'M') {
        const double m_code = std::strtod(word.c_str() + 1, nullptr);
        if (m_code >= 100 && m_code < 200) {
          return "M100-M199 are user M codes: LinuxCNC runs the program of that name, a controller's own extension this one "
                 "does not have (remove the line; M62-M65 switch digital outputs)";
        }
        return "unsupported M code (supported: M0 M1 M2 M30 M3 M4 M5 M6 M7 M8 M9 M48-M53 M62-M65, and M98 M99 as numbered programs)";
      }
      if (!word.empty() && word[0] == 'G') return "unsupported G code (docs/gcode.md lists the supported ones)";
      return "unsupported word";
    }
    case Error::GcodeBadNumber: return "malformed or out-of-range number (an integer part of at most 15 digits; coordinates within +-32767 mm)";
    case Error::GcodeMissingWord:
      if (polar) {
        return "polar coordinates: the current point is at the XY origin, where its angle is undefined: give ^ with @ (G90), "
               "or leave the origin first (a G91 polar move from the origin is indeterminate)";
      }
      if (word == "G41.1" || word == "G42.1") return "G41.1/G42.1 need D (the tool diameter)";
      if (word == "G41" || word == "G42") {
        return "G41/G42 without D use the loaded tool, which has no diameter in the machine file's tool table: give D<tool> of a tool "
               "with a diameter, or G41.1/G42.1 D<diameter>";
      }
      if (g5_1) return "G5.1 needs both I and J (the offset of the control point; LinuxCNC refuses either alone)";
      if (g5) return "G5 needs P and Q, and I and J together";
      if (arc) return "an arc needs I J (centre) or R (radius)";
      if (word.starts_with("R")) return "the radius form cannot make a full circle: give the centre with I J";
      if (word.starts_with("P")) return "a weight P inside a NURBS block needs X or Y";
      return "no motion mode (G0, G1, G2, G3, G5, G5.1, G5.2) is active";
    case Error::GcodeArcRadiusMismatch:
      if (word.starts_with("R")) return "the radius is too small to reach the end point";
      return "radius to end of arc differs from radius to start (allowed: 2.83 mm / 0.283 in, and 0.0283 mm / 0.00283 in beyond "
             "0.1 % of the radius), or the radius is zero";
    case Error::GcodeCannedCycle:
      if (word.starts_with("R")) return "canned cycle: the retract plane R is below the hole bottom Z";
      if (word.starts_with("Q")) return "canned cycle: the peck depth Q must be positive";
      if (word.starts_with("P")) return "canned cycle: the dwell P must be from 0 to 1e6 seconds";
      if (word.starts_with("G86")) return "canned cycle: G86 needs the spindle turning (M3/M4 first), or Z, R and P are missing";
      if (word.starts_with("G73") || word.starts_with("G83")) {
        return "canned cycle: needs X, Y or Z, and Z, R and a positive Q in this block or an earlier block of the series";
      }
      if (word.starts_with("G82") || word.starts_with("G89")) {
        return "canned cycle: needs X, Y or Z, and Z, R and P in this block or an earlier block of the series";
      }
      return "canned cycle: needs X, Y or Z, and Z and R in this block or an earlier block of the series";
    case Error::GcodeCutterCompensation:
      if (word.starts_with("G41") || word.starts_with("G42")) {
        return "cutter radius compensation is already on: G40 first (it cannot be turned on again or change side while on)";
      }
      if (word.starts_with("D")) {
        const std::string tool = word.size() > 1 ? "tool " + word.substr(1) : std::string("the tool D names");  // D#1: no digits
        return tool + " has no diameter in the machine file's tool table (G41.1/G42.1 D<diameter> give the diameter directly)";
      }
      if (word.starts_with("L")) return "the tool orientation L is for lathe tools: this controller compensates mill tools, in G17 and G18 (leave L out or give L0)";
      if (word.starts_with("G17") || word.starts_with("G18") || word.starts_with("G19")) {
        return "the plane cannot change while cutter radius compensation is on (G40 first)";
      }
      if (word.starts_with("G28") || word.starts_with("G30")) return "G28/G30 cannot be used while cutter radius compensation is on (G40 first)";
      if (word.starts_with("G53")) return "G53 (machine coordinates) cannot be used while cutter radius compensation is on (G40 first)";
      if (word.starts_with("G43") || word.starts_with("G49")) {
        return "the tool length offset (G43, G43.1, G49) cannot change while cutter radius compensation is on (G40 first), as in LinuxCNC";
      }
      if (word.starts_with("G10")) return "G10 cannot change the coordinate system in use while cutter radius compensation is on (G40 first)";
      if (word.starts_with("G5")) return "splines (G5, G5.1, G5.2) cannot be compensated: G40 first, or let the CAM offset them";
      if (word.starts_with("G7") || word.starts_with("G8")) return "canned cycles cannot run while cutter radius compensation is on (G40 first)";
      return "this motion cannot be compensated (splines, canned cycles): G40 first";
    case Error::GcodeSplineNotG17: return "splines (G5, G5.1, G5.2) need plane G17 (XY)";
    case Error::GcodeSplineNoTangent: return "G5 without I J must follow a G5 whose end tangent it continues (the first of a series needs I J)";
    case Error::GcodeSyntax:
      return "syntax error (unexpected character, unclosed comment, N not first, or too many words)";
    case Error::GcodeConflictingWords:
      if (polar) {
        return "polar coordinates (@ distance, ^ angle) cannot be mixed with X or Y on one line, and are for motion only "
               "(not with G10, G28, G30, G53, G80, G92)";
      }
      return "cannot appear with the other words of the line (or twice)";
    case Error::GcodeNurbsBlock:
      if (polar) {
        return "a NURBS control point (G5.2) takes X and Y, not polar words: LinuxCNC adds a control point only for X and Y together "
               "(polar words give G5 and G5.1 their end point)";
      }
      if (word.starts_with("G5.3")) return "G5.3 without an open G5.2 block, or with fewer control points than the order L";
      if (word.starts_with("L")) return "the order L must be an integer from 2 to 8, given on the G5.2 line";
      if (word.starts_with("P")) return "a NURBS weight P must be positive";
      if (word.starts_with("M")) return "the program ends inside a G5.2 block";
      if (word.starts_with("G")) return "only X Y P lines and G5.3 may follow G5.2";
      return "too many control points in the G5.2 block";
    default: return std::string(describe(code));
  }
}

/// Why a block was refused for its feed (G93, G94), in LinuxCNC's terms.
std::string feed_refusal_text(machine::FeedRefusal why) {
  switch (why) {
    case machine::FeedRefusal::InverseTimeWithoutF:
      return "F word missing with an inverse-time move: in G93 every G1, G2, G3 needs its own F (the move takes 1/F minutes)";
    case machine::FeedRefusal::NoFeedAfterG94:
      return "no feed rate in force: G94 after G93 leaves none (as in LinuxCNC), give a new F before this feed move";
    case machine::FeedRefusal::SplineInInverseTime:
      return "splines (G5, G5.1, G5.2) cannot run in inverse-time feed mode (G93): LinuxCNC gives them no time of their own; use G94 and F";
    case machine::FeedRefusal::CycleInInverseTime:
      return "cannot use inverse-time feed (G93) with canned cycles, as in LinuxCNC: G94 and F first";
    case machine::FeedRefusal::None: break;
  }
  return {};
}

class GcodeLoader {
 public:
  GcodeLoader(std::string name, const GcodeOptions& options, JobSink* sink = nullptr)
      : sink_(sink), keep_source_lines_(options.keep_source_lines) {
    job_.name = std::move(name);
    for (const auto& [tool, length] : options.tool_length_mm) {
      if (tool < 0 || !interpreter_.set_tool_length_mm(static_cast<std::size_t>(tool), length)) refuse_tool(tool);
    }
    interpreter_.set_home_positions(options.g28_position, options.g30_position);
    for (const auto& [tool, diameter] : options.tool_diameter_mm) {
      if (tool < 0 || !interpreter_.set_tool_diameter_mm(static_cast<std::size_t>(tool), diameter)) refuse_tool(tool);
    }
  }

  Job load(language::ProgramReader reader) {
    reserve_per_line(reader.line_count());
    std::size_t nurbs_line = 0;
    std::size_t nurbs_column = 0;
    std::string nurbs_file;
    write_parameters(reader.parameters());
    while (!interpreter_.ended()) {
      auto program_block = reader.next();
      if (!program_block) break;
      source_ = std::move(program_block->source);
      line_ = source_;
      line_number_ = program_block->line;
      job_line_ = program_block->program_line;
      block_file_ = std::move(program_block->file);
      for (const auto& message : program_block->messages) add_event(JobEventKind::Message, 0, false, trimmed(message.text));
      const Block block = machine_block(*program_block);
      read_offset_parameters(reader.parameters());
      const bool was_in_nurbs = interpreter_.in_nurbs_block();
      const MachinePoint before = interpreter_.position();
      const auto motion = interpreter_.execute(block);
      if (!motion) {
        if (motion.error() == Error::GcodeArcRadiusMismatch) fail_radii(block, motion.where());
        if (interpreter_.refused_feed() != machine::FeedRefusal::None) {
          fail_message(motion.where(), feed_refusal_text(interpreter_.refused_feed()), motion.error());
        }
        if (motion.error() == Error::GcodeUnsupportedWord && rotated_plane_arc(motion.where())) {
          fail_message(motion.where(),
                       "an arc in G18 or G19 cannot run in a rotated coordinate system (G10 L2 R): the rotation about Z tilts its "
                       "plane off the axes, which this controller does not support (use G17 arcs, or a system without rotation)",
                       Error::GcodeUnsupportedWord);
        }
        fail(motion.where(), motion.error());
      }
      if (!was_in_nurbs && interpreter_.in_nurbs_block()) {
        nurbs_line = line_number_;
        nurbs_file = error_file();
        for (const auto& w : block.words()) {
          if (w.letter == 'G' && w.code_tenths == 52) nurbs_column = w.column;
        }
      }
      follow_compensation(motion.value(), before);
      add_events(motion.value(), false);
      if (motion.value().has_pre_rapid) add_rapid(before, motion.value());
      add(motion.value());
      add_events(motion.value(), true);
      write_parameters(reader.parameters());
      hand_over();
    }
    if (compensation_.active()) flush(compensation_.stop());  // the end of the program: the last move ends square
    hand_over();
    if (interpreter_.in_nurbs_block()) {
      line_number_ = nurbs_line;
      line_ = {};
      throw LoadError(SourceLocation{nurbs_file, nurbs_line, nurbs_column, std::nullopt, {}, "G5.2"},
                      "the NURBS block is not closed by G5.3", Error::GcodeNurbsBlock);
    }
    return std::move(job_);
  }

 private:
  using Block = machine::Block<machine_block_capacity>;

  /// An executed line of the language layer as the machine layer's block: letters it does not
  /// know are refused here, with their column.
  Block machine_block(const language::ProgramBlock& program_block) {
    Block block;
    feed_column_ = 0;
    if (program_block.block_delete) block.set_block_delete();
    for (const auto& w : program_block.words) {
      if (!machine::is_supported_letter(w.letter)) fail(w.column, Error::GcodeUnsupportedWord);
      const bool code = w.letter == 'G' || w.letter == 'M';
      const machine::Word word{w.letter, w.value, code ? machine::code_tenths(w.value) : -1,
                               static_cast<std::uint16_t>(std::min<std::size_t>(w.column, 0xFFFF))};
      if (!block.try_push(word)) fail(w.column, Error::GcodeSyntax);
      if (w.letter == 'F') feed_column_ = word.column;
    }
    return block;
  }

  /// Segments made so far (handed over or not): the index the next one gets.
  std::size_t segment_count() const noexcept { return handed_over_ + job_.segments.size(); }

  /// A streamed load: the segments and events made so far go to the sink, checked as load_job_file
  /// checks every segment (their sources are SourceLines: only what messages need).
  void hand_over() {
    if (sink_ == nullptr) return;
    std::size_t e = 0;
    for (std::size_t j = 0; j < job_.segments.size(); ++j) {
      const std::size_t source = job_.source_index[j];
      check_swept_extent(job_.segments[j], job_, source);
      check_parameter_speed(job_.segments[j], job_, source);
      while (e < job_.events.size() && job_.events[e].before_segment <= handed_over_ + j) sink_->event(std::move(job_.events[e++]));
      sink_->segment(job_.segments[j], source, job_.blend_tolerance_mm[j]);
    }
    for (; e < job_.events.size(); ++e) sink_->event(std::move(job_.events[e]));
    if (!keep_source_lines_) {  // checked above: no message needs them any more
      job_.source_lines_from += job_.source_lines.size();
      job_.source_lines.clear();
    }
    handed_over_ += job_.segments.size();
    job_.segments.clear();
    job_.source_index.clear();
    job_.blend_tolerance_mm.clear();
    job_.events.clear();
  }

  /// The system parameters LinuxCNC keeps, in the program's units: #5211-#5213 the G92 offset,
  /// #5220 the coordinate system (1 = G54), #5221 + 20 n the offsets of system n + 1 and #5230 + 20 n
  /// its rotation (degrees), #5400 the tool, #5420-#5422 the position in the coordinate system in use.
  void write_parameters(language::ParameterStore& parameters) {
    for (std::size_t system = 0; system < coordinate_systems; ++system) {
      written_rotations_[system] = interpreter_.rotation_deg(system);
      parameters.set(rotation_parameter(system), written_rotations_[system]);
    }
    const double unit = interpreter_.scale();
    const MachinePoint position = interpreter_.program_position();
    for (std::size_t axis = 0; axis < 3; ++axis) {
      parameters.set(5420 + static_cast<int>(axis), position[axis] / unit);
      for (std::size_t system = 0; system <= coordinate_systems; ++system) {
        const MachinePoint& offset = system == coordinate_systems ? interpreter_.g92_offset() : interpreter_.work_offset(system);
        written_offsets_[system][axis] = offset[axis] / unit;
        parameters.set(offset_parameter(system, axis), written_offsets_[system][axis]);
      }
    }
    parameters.set(5220, static_cast<double>(interpreter_.coordinate_system() + 1));
    parameters.set(5400, static_cast<double>(interpreter_.loaded_tool()));
  }

  /// A program that assigns a work-offset, rotation or G92 parameter changes it, as G10 L2 or G92 would.
  void read_offset_parameters(const language::ParameterStore& parameters) {
    const double unit = interpreter_.scale();
    for (std::size_t system = 0; system < coordinate_systems; ++system) {
      const double value = parameters.get(rotation_parameter(system));
      if (value != written_rotations_[system]) interpreter_.set_rotation_deg(system, value);
    }
    for (std::size_t system = 0; system <= coordinate_systems; ++system) {
      MachinePoint offset = system == coordinate_systems ? interpreter_.g92_offset() : interpreter_.work_offset(system);
      bool changed = false;
      for (std::size_t axis = 0; axis < 3; ++axis) {
        const double value = parameters.get(offset_parameter(system, axis));
        if (value == written_offsets_[system][axis]) continue;
        offset[axis] = value * unit;
        changed = true;
      }
      if (!changed) continue;
      if (system == coordinate_systems) {
        interpreter_.set_g92_offset(offset);
      } else {
        interpreter_.set_work_offset(system, offset);
      }
    }
  }

  /// Work coordinate systems G54 … G59.3; index coordinate_systems stands for the G92 offset.
  static constexpr std::size_t coordinate_systems = 9;
  static int offset_parameter(std::size_t system, std::size_t axis) {
    const int a = static_cast<int>(axis);
    return system == coordinate_systems ? 5211 + a : 5221 + 20 * static_cast<int>(system) + a;
  }
  /// LinuxCNC's parameter of the rotation of system `system` (0 = G54: #5230).
  static int rotation_parameter(std::size_t system) { return 5230 + 20 * static_cast<int>(system); }

  /// A tool table the interpreter cannot hold (the machine loader checks the same bounds first).
  [[noreturn]] void refuse_tool(int tool) const {
    throw LoadError(SourceLocation{job_.name, 0, 0, std::nullopt, {}, "tools"},
                    "tool " + std::to_string(tool) + ": tool numbers are 0 .. " + std::to_string(Interpreter::max_tool_number) +
                        ", at most " + std::to_string(Interpreter::max_tools) + " tools",
                    Error::InvalidMachine);
  }

  /// Whether the word at `column` is that of a G18/G19 arc the interpreter refused for the rotation of its system.
  bool rotated_plane_arc(std::size_t column) const {
    const std::string word = word_at(line_, column);
    if (word.empty()) return false;
    const std::size_t digits = word.find_first_not_of('0', 1);  // "G02" is G2
    const bool arc_code = word[0] == 'G' && digits != std::string::npos && (word.substr(digits) == "2" || word.substr(digits) == "3");
    const bool arc_word = arc_code || std::string_view("XYZIJKRP").find(word[0]) != std::string_view::npos;
    const std::int32_t mode = interpreter_.motion_mode();
    return arc_word && (mode == 20 || mode == 30) && interpreter_.plane() != machine::Plane::XY &&
           interpreter_.rotation_deg(interpreter_.coordinate_system()) != 0;
  }

  /// The file of the line being executed, as messages name it: the program or a subroutine file.
  [[nodiscard]] const std::string& error_file() const { return block_file_.empty() ? job_.name : block_file_; }

  [[noreturn]] void fail(std::size_t column, Error code) {
    const std::string word = word_at(line_, column);
    throw LoadError(SourceLocation{error_file(), line_number_, column, std::nullopt, {}, word}, explain(code, word), code);
  }

  /// GcodeArcRadiusMismatch of a centre-form arc, with both radii as the interpreter measured them
  /// (LinuxCNC's message quotes them too); an R-form arc gets the message of its R word.
  [[noreturn]] void fail_radii(const Block& block, std::size_t column) {
    if (block.find('R') != nullptr) fail(column, Error::GcodeArcRadiusMismatch);
    const auto [r0, r1] = interpreter_.refused_arc_radii();
    const char* allowed = interpreter_.units() == machine::Units::Inches
                              ? "allowed: 0.283 in, and 0.00283 in beyond 0.1 % of the radius (LinuxCNC's 2*0.001*sqrt(2) in)"
                              : "allowed: 2.83 mm, and 0.0283 mm beyond 0.1 % of the radius (LinuxCNC's 2*0.01*sqrt(2) mm)";
    fail_message(column,
                 std::fmin(r0, r1) < machine::arc_zero_radius_mm ? std::string("zero-radius arc: the centre is on the start or end point")
                         : "radius to end of arc differs from radius to start: start radius " + format_number(r0) +
                               " mm, end radius " + format_number(r1) + " mm, difference " + format_number(std::fabs(r1 - r0)) +
                               " mm (" + allowed + ")",
                 Error::GcodeArcRadiusMismatch);
  }

  [[noreturn]] void fail_message(std::size_t column, const std::string& message, Error code) {
    throw LoadError(SourceLocation{error_file(), line_number_, column, std::nullopt, {}, word_at(line_, column)}, message, code);
  }

  /// A point in mm on the Q16.16 grid.
  MachinePoint grid(const MachinePoint& p, std::size_t column) {
    MachinePoint q{};
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      const auto fixed = Q16_16::from_double(p[axis]);
      if (!fixed) fail_message(column, "coordinate " + format_number(p[axis]) + " mm is outside the Q16.16 range", Error::FixedOverflow);
      q[axis] = fixed.value().to_double();
    }
    return q;
  }

  /// A weight or a feed on the Q16.16 grid, as the wire carries it (round_for_wire, as the job loader).
  double wire_value(double value, WireQuantity quantity, std::size_t column, std::string_view name = {}) {
    const auto rounded = round_for_wire(value, quantity, name);
    if (!rounded) fail_message(column, rounded.problem, rounded.code);
    return rounded.value;
  }

  /// The column of the block's F word, or `fallback`.
  std::size_t feed_column(std::size_t fallback) const { return feed_column_ != 0 ? feed_column_ : fallback; }

  PathSegment made(const Result<PathSegment>& segment, std::size_t column) {
    if (!segment) fail_message(column, std::string(describe(segment.error())), segment.error());
    return segment.value();
  }

  /// The block's machine events as job events: those LinuxCNC executes before the motion
  /// (`after` false), or the stops after it (M0/M1/M2/M30).
  void add_events(const machine::Motion& motion, bool after) {
    for (const auto& e : motion.machine_events()) {
      const bool stop = e.kind == machine::MachineEventKind::Pause || e.kind == machine::MachineEventKind::ProgramEnd;
      if (stop != after) continue;
      add_event(job_event_kind(e.kind), e.value, e.flag, word_at(line_, e.column));
    }
  }

  static JobEventKind job_event_kind(machine::MachineEventKind kind) {
    switch (kind) {
      case machine::MachineEventKind::SpindleSpeed: return JobEventKind::SpindleSpeed;
      case machine::MachineEventKind::ToolChange: return JobEventKind::ToolChange;
      case machine::MachineEventKind::SpindleOn: return JobEventKind::SpindleOn;
      case machine::MachineEventKind::SpindleOff: return JobEventKind::SpindleOff;
      case machine::MachineEventKind::CoolantMist: return JobEventKind::CoolantMist;
      case machine::MachineEventKind::CoolantFlood: return JobEventKind::CoolantFlood;
      case machine::MachineEventKind::CoolantOff: return JobEventKind::CoolantOff;
      case machine::MachineEventKind::DigitalOutput: return JobEventKind::DigitalOutput;
      case machine::MachineEventKind::Dwell: return JobEventKind::Dwell;
      case machine::MachineEventKind::Pause: return JobEventKind::ProgramPause;
      case machine::MachineEventKind::ProgramEnd: return JobEventKind::ProgramEnd;
    }
    return JobEventKind::Dwell;
  }

  /// The rapid to G28/G30's intermediate point, before the move home.
  void add_rapid(const MachinePoint& from, const machine::Motion& motion) {
    machine::Motion leg = motion;
    leg.kind = machine::MotionKind::Rapid;
    leg.start = from;
    leg.end = motion.pre_rapid;
    add(leg);
  }

  /// Room for a segment per program line (the reader counted them): the job's vectors then never
  /// move their contents while they grow (a doubling vector of 472-byte PathSegments held up to 2.5
  /// times its segments at once). Pages reserved and never written take no memory.
  void reserve_per_line(std::size_t count) {
    if (sink_ != nullptr) return;  // a streamed load keeps only SourceLines, which grow by doubling: 8 bytes each
    job_.sources.reserve(count);
    job_.segments.reserve(count);
    job_.source_index.reserve(count);
    job_.blend_tolerance_mm.reserve(count);
  }

  /// A motion of the program: through the cutter compensation while it is active.
  void add(const machine::Motion& motion) {
    if (motion.kind == machine::MotionKind::None) return;
    if (!compensation_.active()) {
      emit(motion, job_line_);
      return;
    }
    const bool planar = motion.kind == machine::MotionKind::Rapid || motion.kind == machine::MotionKind::Line ||
                        (motion.kind == machine::MotionKind::Arc && motion.plane == compensation_plane_);
    if (!planar) {  // the interpreter refuses these while compensation is on: this is the exit move
      fail_message(motion.column, "the exit move (the first move after G40) must be a straight line (G0/G1): it goes from the "
                                  "compensated point to the programmed end", Error::GcodeCutterCompensation);
    }
    const MachinePoint start = to_plane(motion.start);
    const MachinePoint end = to_plane(motion.end);
    if (motion.kind != machine::MotionKind::Arc && start[0] == end[0] && start[1] == end[1]) {
      // Along the normal axis alone (Z in G17): where the tool centre is, once the held move's end is known.
      if (compensation_.holding()) {
        held_.push_back(Held{false, {}, motion, job_line_});
      } else {
        emit(at_plane(motion, compensation_.tool()), job_line_);
      }
      return;
    }
    PlanarMove programmed;
    programmed.arc = motion.kind == machine::MotionKind::Arc;
    programmed.rapid = motion.kind == machine::MotionKind::Rapid;
    programmed.start = start;
    programmed.end = end;
    programmed.center = to_plane(motion.center);
    programmed.direction = motion.direction;
    programmed.full_turns = motion.full_turns;
    programmed.tag = next_tag_++;
    moves_[programmed.tag] = MoveInfo{motion, job_line_};
    CompensatedMoves out;
    try {
      out = compensation_.add(programmed);
    } catch (const CompensationError& e) {
      fail_message(motion.column, e.what(), Error::GcodeCutterCompensation);
    }
    flush(out.finished);
    if (out.corner) emit_compensated(*out.corner, true);
  }

  /// G40, G41/G42 as this block's motion has them: starts or stops the compensation first.
  void follow_compensation(const machine::Motion& motion, const MachinePoint& before) {
    const bool wanted = motion.compensation_side != machine::CompensationSide::Off && motion.compensation_radius_mm > 0;
    const bool on = compensation_.active() && !compensation_.exiting();
    if (on && !wanted) flush(compensation_.stop());
    if (wanted && !on) {
      const auto side = motion.compensation_side == machine::CompensationSide::Left ? CutterCompensation::Side::Left
                                                                                    : CutterCompensation::Side::Right;
      // An exit move still to come is in the old plane's coordinates: the tool as a machine point.
      const MachinePoint tool = compensation_.active() ? from_plane(compensation_.tool()) : before;
      compensation_plane_ = interpreter_.plane();
      compensation_.start(side, motion.compensation_radius_mm, to_plane(tool));
    }
  }

  /// A compensated move that became final, then what was held behind it (events, Z moves at its end).
  void flush(const std::optional<PlanarMove>& finished) {
    if (!finished) return;
    emit_compensated(*finished, false);
    for (Held& h : held_) {
      if (h.is_event) {
        h.event.before_segment = segment_count();
        job_.events.push_back(std::move(h.event));
      } else {
        emit(at_plane(h.motion, finished->end), h.line);
      }
    }
    held_.clear();
  }

  /// `motion` moved to the compensation plane's coordinates of `point` (in plane coordinates).
  machine::Motion at_plane(machine::Motion motion, const MachinePoint& point) const {
    const machine::PlaneAxes axes = machine::axes_of(compensation_plane_);
    for (const std::size_t axis : {axes.first, axes.second}) {
      motion.start[axis] = point[axis == axes.first ? 0 : 1];
      motion.end[axis] = motion.start[axis];
    }
    return motion;
  }

  /// A machine point in the compensation plane's coordinates: [0] its first axis, [1] its second,
  /// [2] the normal (G17: X Y Z; G18: Z X Y), as CutterCompensation works; from_plane goes back.
  MachinePoint to_plane(const MachinePoint& p) const {
    const machine::PlaneAxes axes = machine::axes_of(compensation_plane_);
    return MachinePoint{{p[axes.first], p[axes.second], p[axes.normal]}};
  }
  MachinePoint from_plane(const MachinePoint& q) const {
    const machine::PlaneAxes axes = machine::axes_of(compensation_plane_);
    MachinePoint p{};
    p[axes.first] = q[0];
    p[axes.second] = q[1];
    p[axes.normal] = q[2];
    return p;
  }

  /// A move of the compensated path as a segment of its program line (a corner arc: the next move's).
  void emit_compensated(const PlanarMove& move, bool corner) {
    const auto info = moves_.find(move.tag);
    machine::Motion motion = info->second.motion;
    motion.kind = move.arc ? machine::MotionKind::Arc : (move.rapid ? machine::MotionKind::Rapid : machine::MotionKind::Line);
    motion.start = from_plane(move.start);
    motion.end = from_plane(move.end);
    motion.center = from_plane(move.center);
    motion.plane = compensation_plane_;
    motion.direction = move.direction;
    motion.full_turns = move.full_turns;
    motion.has_pre_rapid = false;
    if (move.arc) {
      const double r0 = std::hypot(move.start[0] - move.center[0], move.start[1] - move.center[1]);
      const double r1 = std::hypot(move.end[0] - move.center[0], move.end[1] - move.center[1]);
      motion.radius_difference_mm = std::fabs(r1 - r0);
    }
    const std::size_t line = info->second.line;
    if (!corner) moves_.erase(info);
    emit(motion, line, corner && move.rapid);
  }

  /// A motion as segments of program line `line`; `rapid_arc`: an arc traversed at rapid speed.
  void emit(const machine::Motion& motion, std::size_t line, bool rapid_arc = false) {
    if (motion.kind == machine::MotionKind::None) return;
    SourceSegment source;
    source.line = line;
    const std::size_t column = motion.column;
    if (motion.kind != machine::MotionKind::Rapid && !rapid_arc && motion.feed_given && motion.feed_mm_per_min == 0) {
      fail_message(feed_column(column), "a feed move at F0: the feed rate is zero (give F > 0; LinuxCNC refuses it too)",
                   Error::GcodeBadNumber);
    }
    source.feed_mm_per_s = motion.kind == machine::MotionKind::Rapid || rapid_arc
                               ? 0.0
                               : wire_value(motion.feed_mm_per_min / seconds_per_minute, WireQuantity::Feed, feed_column(column), "feed (mm/s)");
    std::vector<PathSegment> pieces;
    const MachinePoint start = grid(motion.start, column);
    const MachinePoint end = grid(motion.end, column);
    switch (motion.kind) {
      case machine::MotionKind::Rapid:
      case machine::MotionKind::Line: {
        source.type = motion.kind == machine::MotionKind::Rapid ? SegmentType::Rapid : SegmentType::Line;
        source.degree = 1;
        source.points = {start, end};
        if (start == end) return;  // shorter than the grid: nothing moves
        pieces.push_back(made(PathSegment::make_line(start, end), column));
        pieces.back().set_rapid(motion.kind == machine::MotionKind::Rapid);
        break;
      }
      case machine::MotionKind::Arc: {
        source.type = SegmentType::Arc;
        const MachinePoint center = grid(motion.center, column);
        source.points = {start, end, center};
        if (motion.plane != machine::Plane::XY) {
          add_plane_arc(motion, start, end, source, pieces);
          for (PathSegment& piece : pieces) piece.set_rapid(rapid_arc);  // a G0's corner arc under G18 compensation
          break;
        }
        const double tolerance = motion.radius_difference_mm + quantisation_radius_slack_mm;
        pieces.push_back(made(PathSegment::make_arc(start, end, center, motion.direction, motion.full_turns, tolerance), column));
        pieces.back().set_rapid(rapid_arc);
        break;
      }
      case machine::MotionKind::Cubic:
      case machine::MotionKind::Quadratic: {
        source.type = SegmentType::Bezier;
        const std::size_t count = motion.kind == machine::MotionKind::Cubic ? 4 : 3;
        for (std::size_t i = 0; i < count; ++i) source.points.push_back(grid(motion.control[i], column));
        source.degree = count - 1;
        pieces.push_back(made(PathSegment::make_bezier(source.points), column));
        break;
      }
      case machine::MotionKind::Nurbs: add_nurbs(motion, source, pieces); break;
      case machine::MotionKind::Cycle: add_cycle(motion); return;
      case machine::MotionKind::None: return;
    }
    if (source.breaks.empty()) source.breaks = {0.0, 1.0};
    const std::size_t index = source_count(job_);
    source.first_piece = segment_count();
    for (auto& piece : pieces) {
      piece.set_feed_mm_per_s(source.type == SegmentType::Rapid ? 0.0 : source.feed_mm_per_s);
      job_.segments.push_back(piece);
      job_.source_index.push_back(index);
      job_.blend_tolerance_mm.push_back(motion.path_tolerance_mm);  // G64 P / G61 at the joint into it
    }
    if (source.type == SegmentType::Rapid) source.feed_mm_per_s = 0;
    if (sink_ != nullptr) {
      // A streamed load: 8 bytes a segment instead of 136.
      static_assert(language::default_max_program_lines <= 0xFFFF'FFFFu, "a line number fits a SourceLine");
      job_.source_lines.push_back(SourceLine{static_cast<std::uint32_t>(source.line), source.type});
    } else {
      job_.sources.push_back(std::move(source));
    }
  }

  /// An arc in G18 or G19: rational quadratic pieces of at most a quarter turn, exact circles (the
  /// radius goes linearly from start to end within the checked difference). A helix's normal axis
  /// moves linearly per piece; pieces are halved until its pitch error is below helix_tolerance_mm.
  void add_plane_arc(const machine::Motion& motion, const MachinePoint& start, const MachinePoint& end, SourceSegment& source,
                     std::vector<PathSegment>& pieces) {
    const std::size_t column = motion.column;
    const machine::PlaneAxes axes = machine::axes_of(motion.plane);
    const double cu = motion.center[axes.first];
    const double cv = motion.center[axes.second];
    // The sweep as the core measures an XY arc (direction, full circle, extra turns), in the plane's
    // own coordinates (u, v) = (first, second), counter-clockwise seen from the positive normal.
    const auto in_plane = [&axes](const MachinePoint& p) { return MachinePoint{{p[axes.first], p[axes.second], 0.0}}; };
    const PathSegment planar = made(PathSegment::make_arc(in_plane(start), in_plane(end), in_plane(motion.center), motion.direction,
                                                          motion.full_turns, motion.radius_difference_mm + quantisation_radius_slack_mm),
                                    column);
    const double sign = planar.arc_sweep_rad() >= 0 ? 1.0 : -1.0;
    const double sweep = std::fabs(planar.arc_sweep_rad());
    const double a0 = std::atan2(start[axes.second] - cv, start[axes.first] - cu);
    const double r0 = std::hypot(start[axes.first] - cu, start[axes.second] - cv);
    const double r1 = std::hypot(end[axes.first] - cu, end[axes.second] - cv);
    const double rise = end[axes.normal] - start[axes.normal];
    std::size_t count = static_cast<std::size_t>(std::ceil(sweep / (std::numbers::pi / 2) - 1e-12));
    if (count == 0) count = 1;
    while (count < max_arc_pieces && std::fabs(rise / static_cast<double>(count)) * helix_pitch_error(sweep / static_cast<double>(count)) >
                                         helix_tolerance_mm) {
      count *= 2;
    }
    const double step = sweep / static_cast<double>(count);
    const double weight = wire_value(std::cos(step / 2), WireQuantity::Weight, column);
    const auto at = [&](double angle, double radius, double normal) {
      MachinePoint p{};
      p[axes.first] = cu + radius * std::cos(angle);
      p[axes.second] = cv + radius * std::sin(angle);
      p[axes.normal] = normal;
      return p;
    };
    MachinePoint from = start;
    for (std::size_t k = 0; k < count; ++k) {
      const double f0 = static_cast<double>(k) / static_cast<double>(count);
      const double f1 = static_cast<double>(k + 1) / static_cast<double>(count);
      const double mid_radius = r0 + (r1 - r0) * (f0 + f1) / 2;
      const double mid_normal = start[axes.normal] + rise * (f0 + f1) / 2;
      const MachinePoint control = grid(at(a0 + sign * step * (static_cast<double>(k) + 0.5), mid_radius / std::cos(step / 2), mid_normal), column);
      const MachinePoint to = k + 1 == count ? end : grid(at(a0 + sign * step * static_cast<double>(k + 1), r0 + (r1 - r0) * f1,
                                                          start[axes.normal] + rise * f1), column);
      const std::vector<MachinePoint> points{from, control, to};
      const std::vector<double> weights{1.0, weight, 1.0};
      pieces.push_back(made(PathSegment::make_rational_bezier(points, weights), column));
      source.breaks.push_back(f0);
      from = to;
    }
    source.breaks.push_back(1.0);
  }

  /// The largest difference, as a fraction of a piece's rise, between the normal coordinate of a
  /// rational quadratic arc piece of angle `step` (the middle control point at the mean height) and
  /// a true helix's, which rises in proportion to the angle. Sampled at 64 parameters.
  static double helix_pitch_error(double step) {
    const double w = std::cos(step / 2);
    double worst = 0;
    for (int i = 1; i < 64; ++i) {
      const double t = i / 64.0;
      const double b0 = (1 - t) * (1 - t);
      const double b1 = 2 * t * (1 - t);
      const double b2 = t * t;
      const double d = b0 + w * b1 + b2;
      const double x = (b0 * std::cos(step / 2) + b1 + b2 * std::cos(step / 2)) / d;  // w·(1/w) = 1 for the middle point
      const double y = (-b0 * std::sin(step / 2) + b2 * std::sin(step / 2)) / d;
      const double by_angle = (std::atan2(y, x) + step / 2) / step;
      const double rational = (w * b1 / 2 + b2) / d;
      worst = std::max(worst, std::fabs(rational - by_angle));
    }
    return worst;
  }

  /// A canned cycle: its rapids and feeds as lines of the cycle's program line, its dwells and
  /// G86's spindle stop and restart as events between them.
  void add_cycle(const machine::Motion& motion) {
    machine::Motion leg = motion;
    leg.kind = machine::MotionKind::Rapid;
    leg.start = motion.start;
    const std::string word = "G" + std::to_string(motion.cycle.code);  // also on the lines that only give X Y
    machine::expand_cycle(motion.cycle, motion.start, [&](const machine::CycleStep& step) {
      switch (step.kind) {
        case machine::CycleStepKind::Rapid:
        case machine::CycleStepKind::Feed:
          leg.kind = step.kind == machine::CycleStepKind::Rapid ? machine::MotionKind::Rapid : machine::MotionKind::Line;
          leg.end = step.end;
          emit(leg, job_line_);
          leg.start = step.end;
          return;
        case machine::CycleStepKind::Dwell: add_event(JobEventKind::Dwell, step.seconds, false, word); return;
        case machine::CycleStepKind::SpindleStop: add_event(JobEventKind::SpindleOff, 0, false, word); return;
        case machine::CycleStepKind::SpindleStart:
          add_event(JobEventKind::SpindleOn, interpreter_.spindle_rpm(), interpreter_.spindle_counter_clockwise(), word);
          return;
      }
    });
  }

  void add_event(JobEventKind kind, double value, bool flag, const std::string& text) {
    JobEvent event;
    event.kind = kind;
    event.before_segment = segment_count();
    event.value = value;
    event.flag = flag;
    event.line = job_line_;
    event.text = text;
    if (compensation_.holding()) {
      held_.push_back(Held{true, std::move(event), {}, 0});  // after the held move
      return;
    }
    job_.events.push_back(std::move(event));
  }

  void add_nurbs(const machine::Motion& motion, SourceSegment& source, std::vector<PathSegment>& pieces) {
    const std::size_t column = motion.column;
    source.type = SegmentType::Nurbs;
    const auto points = interpreter_.nurbs_points();
    const auto weights = interpreter_.nurbs_weights();
    for (const auto& p : points) source.points.push_back(grid(p, column));
    for (const double w : weights) source.weights.push_back(wire_value(w, WireQuantity::Weight, column));
    const std::size_t n = points.size();
    const std::size_t p = motion.nurbs_order - 1;
    source.degree = p;
    // Clamped uniform knots: p+1 zeros, 1 .. n-p-1, p+1 times n-p.
    for (std::size_t i = 0; i <= p; ++i) source.knots.push_back(0.0);
    for (std::size_t i = 1; i + p < n; ++i) source.knots.push_back(static_cast<double>(i));
    for (std::size_t i = 0; i <= p; ++i) source.knots.push_back(static_cast<double>(n - p));
    const auto nurbs = RationalSpline::create(source.points, source.weights, source.knots, p);
    if (!nurbs) fail_message(column, "NURBS block: " + std::string(describe(nurbs.error())), Error::GcodeNurbsBlock);
    const auto extracted = for_each_bezier(nurbs.value(), [&](const auto& piece) {
      std::vector<MachinePoint> control;
      std::vector<double> piece_weights;
      for (const auto& c : piece.curve.control_points()) control.push_back(grid(c, column));
      for (std::size_t i = 0; i <= piece.curve.degree(); ++i) piece_weights.push_back(wire_value(piece.curve.weight(i), WireQuantity::Weight, column));
      const auto segment = PathSegment::make_rational_bezier(control, piece_weights);
      if (!segment) {
        fail_message(column, "NURBS block: the piece on knot span [" + format_number(piece.start) + ", " + format_number(piece.end) +
                                 "]: " + std::string(describe(segment.error())),
                     Error::GcodeNurbsBlock);
      }
      pieces.push_back(segment.value());
      if (source.breaks.empty()) source.breaks.push_back(piece.start);
      source.breaks.push_back(piece.end);
    });
    if (!extracted) fail_message(column, "NURBS block: " + std::string(describe(extracted.error())), Error::GcodeNurbsBlock);
  }

  /// What waits behind a held compensated move: an event, or a Z move (at that move's end).
  struct Held {
    bool is_event = false;
    JobEvent event;
    machine::Motion motion;
    std::size_t line = 0;
  };
  /// A programmed move inside the compensation, by tag: its words and line.
  struct MoveInfo {
    machine::Motion motion;
    std::size_t line = 0;
  };

  Job job_;
  JobSink* sink_ = nullptr;          ///< a streamed load's receiver (nullptr: the whole job is kept)
  std::size_t handed_over_ = 0;      ///< segments handed to the sink
  bool keep_source_lines_ = true;    ///< GcodeOptions::keep_source_lines
  Interpreter interpreter_;
  CutterCompensation compensation_;
  machine::Plane compensation_plane_ = machine::Plane::XY;  ///< the plane of the compensation in force (G17 or G18)
  std::vector<Held> held_;
  std::map<std::size_t, MoveInfo> moves_;
  std::size_t next_tag_ = 0;
  std::string source_;     ///< the line being executed, as written
  std::size_t feed_column_ = 0;  ///< the column of its F word, 0 if none
  std::array<std::array<double, 3>, 10> written_offsets_{};  ///< the offset parameters as last written (program units)
  std::array<double, 9> written_rotations_{};  ///< the rotation parameters as last written (degrees)
  std::string_view line_;
  std::size_t line_number_ = 0;  ///< its line in its file, for messages
  std::string block_file_;       ///< its subroutine file, empty in the program (ProgramBlock::file)
  /// The line the job's segments and events name, in the program: in a subroutine file, the
  /// program's line that called into it (ProgramBlock::program_line), since a job names one file.
  std::size_t job_line_ = 0;
};

/// How the language layer reads the program: the subroutine folders given.
language::ProgramOptions program_options(const GcodeOptions& options) {
  language::ProgramOptions program;
  program.subroutine_path = options.subroutine_path;
  return program;
}

}  // namespace

Job parse_gcode_job(std::string_view text, std::string name) { return parse_gcode_job(text, std::move(name), GcodeOptions{}); }

Job parse_gcode_job(std::string_view text, std::string name, const GcodeOptions& options) {
  GcodeLoader loader(name, options);
  return loader.load(language::ProgramReader(text, std::move(name), program_options(options)));
}

Job parse_gcode_job(std::string_view text, std::string name, const GcodeOptions& options, JobSink& sink) {
  GcodeLoader loader(name, options, &sink);
  return loader.load(language::ProgramReader(text, std::move(name), program_options(options)));
}

// The file is read as a stream (ProgramReader::open_file): its text is never held whole.
Job import_gcode(const std::filesystem::path& path, const GcodeOptions& options, JobSink& sink) {
  GcodeLoader loader(path.string(), options, &sink);
  return loader.load(language::ProgramReader::open_file(path, path.string(), program_options(options)));
}

Job import_gcode(const std::filesystem::path& path) { return import_gcode(path, GcodeOptions{}); }

Job import_gcode(const std::filesystem::path& path, const GcodeOptions& options) {
  GcodeLoader loader(path.string(), options);
  return loader.load(language::ProgramReader::open_file(path, path.string(), program_options(options)));
}

}  // namespace curvestep::host
