// SPDX-License-Identifier: MIT
// Umbrella header of curvestep::gcode: the line parser and the modal interpreter.
#pragma once

#include <curvestep/gcode/canned_cycle.hpp>
#include <curvestep/gcode/interpreter.hpp>
#include <curvestep/gcode/inverse_time.hpp>
#include <curvestep/gcode/parser.hpp>
#include <curvestep/gcode/xy_rotation.hpp>
