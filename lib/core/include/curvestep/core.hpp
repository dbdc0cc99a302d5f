// SPDX-License-Identifier: MIT
// Umbrella header for curvestep::core: fixed point, vectors and curves. Allocation-free.
#pragma once

#include <curvestep/core/bspline/basis.hpp>
#include <curvestep/core/bspline/bezier_extraction.hpp>
#include <curvestep/core/bspline/bspline.hpp>
#include <curvestep/core/bspline/conics.hpp>
#include <curvestep/core/bspline/knot_vector.hpp>
#include <curvestep/core/bspline/nurbs.hpp>
#include <curvestep/core/contract.hpp>
#include <curvestep/core/curve/arc_length.hpp>
#include <curvestep/core/curve/bernstein.hpp>
#include <curvestep/core/curve/bezier.hpp>
#include <curvestep/core/curve/circular_arc.hpp>
#include <curvestep/core/curve/composite_bezier.hpp>
#include <curvestep/core/curve/continuity.hpp>
#include <curvestep/core/curve/curvature.hpp>
#include <curvestep/core/curve/power_basis.hpp>
#include <curvestep/core/curve/rational_bezier.hpp>
#include <curvestep/core/error.hpp>
#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/geometry/bounding_box.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/interpolation/catmull_rom.hpp>
#include <curvestep/core/interpolation/cubic_spline.hpp>
#include <curvestep/core/interpolation/hermite.hpp>
#include <curvestep/core/interpolation/parametrization.hpp>
#include <curvestep/core/interpolation/quadratic_spline.hpp>
#include <curvestep/core/interpolation/tridiagonal.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/core/scalar.hpp>
#include <curvestep/core/subdivision/limit.hpp>
#include <curvestep/core/subdivision/refinable_polygon.hpp>
#include <curvestep/core/subdivision/refine.hpp>
#include <curvestep/core/subdivision/subdivision_mask.hpp>
