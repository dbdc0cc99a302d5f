// SPDX-License-Identifier: MIT
// Machine files (JSON, docs/job_format.md): limits, rates and axes, mapped onto MachineLimits.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/host/load_error.hpp>

namespace curvestep::host {

/// Loads a machine file and validates it (MachineLimits::validate). Throws LoadError naming the
/// file, line and field, or std::runtime_error if the file cannot be read.
[[nodiscard]] MachineLimits load_machine(const std::filesystem::path& path);

/// Parses machine text; `name` is used in error messages as the file name.
[[nodiscard]] MachineLimits parse_machine(std::string_view text, std::string name);

/// The machine-file key of a LimitField ("v_max", "axes"."y"."a_max").
[[nodiscard]] std::string machine_field_name(LimitField field, std::size_t axis = 0);

}  // namespace curvestep::host
