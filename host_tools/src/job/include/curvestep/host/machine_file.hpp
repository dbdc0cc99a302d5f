// SPDX-License-Identifier: MIT
// Machine files (JSON, docs/job_format.md): limits, rates and axes, mapped onto MachineLimits, and
// the optional "gpio" section (which Linux GPIO lines drive the axes, for boards/host) and "pen"
// section (a plotter pen on z).
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/host/load_error.hpp>

namespace curvestep::host {

/// One axis's wiring in the "gpio" section: {"step": "GPIO17", "dir": "GPIO27", "invert_dir": false}.
struct GpioAxisWiring {
  std::string step;         ///< name of the step line (as gpioinfo lists it)
  std::string dir;          ///< name of the direction line
  bool invert_dir = false;  ///< the positive direction is the low level of the direction line
};

/// Digital outputs a "gpio" section may wire (M62-M65 P0 .. P63).
inline constexpr std::size_t max_digital_outputs = 64;

/// The "gpio" section: a chip and, per axis, its step and direction lines (no entry: not wired);
/// optionally the machine outputs' lines (empty: not wired): "spindle": {"enable": L,
/// "direction": L}, "coolant": {"mist": L, "flood": L}, "outputs": [L0, L1, ...] (M62-M65 P0, P1, ...).
/// A servo pen's line is the "pen" section's "line" (on this chip).
struct GpioWiring {
  std::string chip;                                              ///< "gpiochip0", "/dev/gpiochip0" or "0"
  std::array<std::optional<GpioAxisWiring>, motion_axes> axes{};  ///< x, y, z
  std::string spindle_enable;         ///< high while the spindle turns (M3/M4)
  std::string spindle_direction;      ///< high for counter-clockwise (M4)
  std::string coolant_mist;           ///< M7
  std::string coolant_flood;          ///< M8
  std::vector<std::string> outputs;   ///< digital outputs 0, 1, ...
};

/// A tool of the "tools" table: its length (G43 H) and cutter diameter (G41/G42 D), mm.
struct MachineTool {
  double length_mm = 0;
  std::optional<double> diameter_mm;  ///< none: G41/G42 with this tool is refused
};

/// How far an axis may go, mm in machine coordinates: low <= position <= high.
struct AxisTravel {
  double low_mm = 0;
  double high_mm = 0;
};

/// The travel of x, y, z (none: the axis is not limited).
using MachineTravel = std::array<std::optional<AxisTravel>, motion_axes>;

/// Tool numbers a "tools" table may hold (0 .. max_tool_number; tool 0 is "no tool"), as the G-code
/// interpreter's T, H and D words (CAM posts number tools freely: T102, T1001).
inline constexpr int max_tool_number = 99999;
/// Tools a "tools" table may list (the interpreter's table size).
inline constexpr std::size_t max_tool_table_size = 100;

/// The "pen" section: a plotter pen on the z axis, {"axis": "z", "up": 5, "down": 0, "feed": 20},
/// or on a servo, {"axis": "servo", "line": "GPIO18", "up_pulse_us": 1000, "down_pulse_us": 2000,
/// "settle": 0.15}. SVG jobs then lift the pen for every rapid between subpaths (job_pipeline.hpp,
/// pen_moves.hpp): on z by moves, on a servo by PenUp/PenDown events each followed by a dwell of
/// the settle time (an exact stop; the controller's board drives the servo from its `pen` hook).
/// Heights and the feed are on the Q16.16 grid the wire carries.
struct PenModel {
  bool servo = false;        ///< a servo pen ("axis": "servo"), else a pen on z
  double up_mm = 0;          ///< z: z of the lifted pen, mm
  double down_mm = 0;        ///< z: z of the pen on the paper, mm (differs from up_mm)
  double feed_mm_per_s = 0;  ///< z: feed of the move down onto the paper, mm/s (> 0); the lift is a rapid
  std::string line;          ///< servo: the PWM/GPIO line the board drives it on
  double up_pulse_us = 0;    ///< servo: pulse width of the lifted pen, microseconds (500 .. 2500)
  double down_pulse_us = 0;  ///< servo: pulse width of the pen on the paper (differs from up)
  double settle_s = 0;       ///< servo: time it takes to move, s (0 .. 10): the dwell after each pen move
};

/// Largest "blend_tolerance" a machine file may give, mm.
inline constexpr double max_blend_tolerance_mm = 10;

/// Everything a machine file holds.
struct MachineFile {
  std::string name;                ///< the file's name, for messages
  MachineLimits limits;            ///< planning and stepping limits, validated
  std::optional<GpioWiring> gpio;  ///< the "gpio" section, if present (validated)
  std::optional<PenModel> pen;     ///< the "pen" section, if present (validated)
  /// "blend_tolerance": path smoothing's largest deviation from the programmed path, mm (0 = off,
  /// the default; G64 P overrides it per move). Host-side: the controller gets smoothed segments.
  double blend_tolerance_mm = 0;
  /// "tools": [{"number": 1, "length": 12.5, "diameter": 6}, ...]: G43 H and G41/G42 D read it.
  std::map<int, MachineTool> tools;
  /// "g28", "g30": [x, y, z], the positions G28 and G30 go to (machine coordinates, mm); machine 0 if absent.
  std::optional<MachinePoint> g28_position;
  std::optional<MachinePoint> g30_position;
  /// "axes"."x"."travel": [low, high], mm: soft limits. Every job is checked against them before
  /// anything moves (its swept extent, arcs included) and the controller gets them.
  MachineTravel travel{};
};

/// The wiring of a machine file: only its "gpio" and "pen" sections, validated as in a whole
/// machine file, other keys not read (`curvestep device --gpio`: the limits come from the host).
struct MachineWiring {
  std::optional<GpioWiring> gpio;  ///< the "gpio" section, if present
  std::optional<PenModel> pen;     ///< the "pen" section, if present
};

/// Loads the wiring of a machine file; throws as load_machine.
[[nodiscard]] MachineWiring load_machine_wiring(const std::filesystem::path& path);

/// Loads a machine file with its optional "gpio" section; throws as load_machine.
[[nodiscard]] MachineFile load_machine_file(const std::filesystem::path& path);

/// Parses machine text with its optional "gpio" section; `name` is the file name in errors.
[[nodiscard]] MachineFile parse_machine_file(std::string_view text, std::string name);

/// Loads a machine file and validates it (MachineLimits::validate). Throws LoadError naming the
/// file, line and field, or std::runtime_error if the file cannot be read.
[[nodiscard]] MachineLimits load_machine(const std::filesystem::path& path);

/// Parses machine text; `name` is used in error messages as the file name.
[[nodiscard]] MachineLimits parse_machine(std::string_view text, std::string name);

/// The machine-file key of a LimitField ("v_max", "axes"."y"."a_max").
[[nodiscard]] std::string machine_field_name(LimitField field, std::size_t axis = 0);

}  // namespace curvestep::host
