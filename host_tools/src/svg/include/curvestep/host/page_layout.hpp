// SPDX-License-Identifier: MIT
// vpype-style page handling for imported drawings: a page size (A4, letter, WxH), landscape,
// rotation by quarter turns, centring, scaling to fit within margins, and the check that the
// drawing fits the page before anything moves (the machine file has no travel range yet).
//
// The layout is one similarity transform (uniform scale, rotation by a multiple of 90°, translation)
// of every segment's control points: lines, Béziers and rational Béziers (with unchanged weights)
// stay the exact image of the drawn curves. Points are rounded to Q16.16 again afterwards.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/host/job.hpp>

namespace curvestep::host {

/// A page in millimetres, as named on the command line.
struct PageSize {
  double width_mm = 0;   ///< portrait width
  double height_mm = 0;  ///< portrait height
  std::string name;      ///< "a4", "210x297mm", ...
};

/// "a4", "a3", "a5", "letter", "legal", "tabloid" or "WxH" with a unit mm, cm or in ("210x297mm",
/// "8.5x11in", "21cmx29.7cm"). std::invalid_argument naming what is wrong.
[[nodiscard]] PageSize parse_page_size(std::string_view text);

/// A length with a unit mm, cm or in, or a plain number of mm ("10", "1cm", "0.5in"). std::invalid_argument.
[[nodiscard]] double parse_page_length(std::string_view text);

/// How to place a drawing on the page.
struct PageLayout {
  std::optional<PageSize> page;  ///< --page; the overflow check needs it, --center and --fit too
  bool landscape = false;        ///< --landscape: the page's longer side along x (a page given as W x H is used as given otherwise)
  bool center = false;           ///< --center: the drawing's bounding box centred on the page
  bool fit = false;              ///< --fit: scaled uniformly to the page minus the margins, centred
  double margin_mm = 0;          ///< --margin: kept free on every side by --fit
  int rotate_deg = 0;            ///< --rotate: 0, 90, 180 or 270, clockwise as seen on the page
  /// True if the layout changes or checks anything.
  [[nodiscard]] bool active() const noexcept { return page.has_value() || rotate_deg != 0 || center || fit; }
};

/// What a layout did.
struct PageLayoutReport {
  double scale = 1;               ///< uniform scale applied
  double page_width_mm = 0;       ///< the page as used (after --landscape), 0 without a page
  double page_height_mm = 0;      ///< the page as used
  MachinePoint low{};             ///< the drawing's bounding box after the layout
  MachinePoint high{};            ///< the drawing's bounding box after the layout
  std::string note;               ///< one line for the user
};

/// The tight bounding box of the job's drawing (non-rapid) segments, curves included; nullopt if none.
[[nodiscard]] std::optional<std::pair<MachinePoint, MachinePoint>> drawing_extent(const Job& job);

/// How far a drawing from `low` to `high` (mm) reaches beyond a page of width × height with its
/// corner at the origin: "26.5 mm below the page, 3 mm right of the page", or empty if it fits
/// (one Q16.16 step of slack).
[[nodiscard]] std::string page_overflow(const MachinePoint& low, const MachinePoint& high, double width_mm, double height_mm);

/// Lays the drawing of `job` (lines, Béziers, rational Béziers and rapids, one piece per source:
/// an imported SVG) out on the page: rotation about the drawing's centre, then with --fit the scale
/// s = min((W − 2m)/w, (H − 2m)/h) and centring, with --center centring alone. Rapids are rebuilt
/// between the moved subpaths, the first from `start`. Throws LoadError (OutsideTravel) naming the
/// overflow in mm if a page is given and the drawing leaves it, std::invalid_argument for options
/// that do not fit together or a job of other segment types.
PageLayoutReport lay_out_on_page(Job& job, const PageLayout& layout, const MachinePoint& start = {});

}  // namespace curvestep::host
