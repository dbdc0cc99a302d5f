// SPDX-License-Identifier: MIT
// Internal: drawn subpaths -> the SvgImport (optional greedy reordering, rapids, feed, sources).
#pragma once

#include <string>
#include <vector>

#include <curvestep/host/svg_import.hpp>

#include "svg_diagnostics.hpp"
#include "svg_layers.hpp"
#include "svg_machine.hpp"

namespace curvestep::host::svg {

/// The job of `drawn` (reordered within each layer if options.optimize), with travel figures and
/// `warnings`; a LayerChange event before the first segment of each layer after the first
/// (`layers`: what DrawnSubpath::layer indexes; empty: no layers). LoadError for a start point outside Q16.16, a feed the wire cannot carry or an unusable piece.
[[nodiscard]] SvgImport build_import(const Diagnostics& diagnostics, std::vector<DrawnSubpath> drawn, const SvgOptions& options,
                                     std::vector<std::string> warnings, const std::vector<Layer>& layers = {});

}  // namespace curvestep::host::svg
