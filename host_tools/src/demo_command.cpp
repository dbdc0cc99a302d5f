// SPDX-License-Identifier: MIT
// `curvestep demo`: builds a bundled path of cubic Béziers and exact arcs, samples it in Q16.16
// and in double, and writes the points (CSV) and a plot (SVG) to the output folder.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <curvestep/core.hpp>
#include <curvestep/core/error_text.hpp>

#include "command_registry.hpp"
#include "svg_plot.hpp"

namespace curvestep::host {
namespace {

using Point = std::array<double, 2>;

struct DemoOptions {
  std::string out = "build/demo";
  int samples_per_segment = 64;
};

// A plotter-style drawing: a wave of C1-joined cubics closed by a semicircle.
std::vector<std::array<Point, 4>> demo_cubics() {
  return {{{{0, 0}, {20, 40}, {40, -40}, {60, 0}}},
          {{{60, 0}, {80, 40}, {100, -40}, {120, 0}}},
          {{{120, 0}, {140, 40}, {160, 40}, {160, 60}}}};
}

template <Scalar S>
std::vector<Point> sample_path(int samples_per_segment, double& max_difference_to_double) {
  std::vector<Point> points;
  max_difference_to_double = 0;
  auto convert = [](const Point& p) {
    const auto v = vec_from_doubles<S, 2>(p);
    if (!v) throw std::runtime_error(std::string("demo point out of range: ") + std::string(error_name(v.error())));
    return v.value();
  };
  for (const auto& cubic : demo_cubics()) {
    std::array<Vec2<S>, 4> control{};
    std::array<Vec2<double>, 4> reference{};
    for (std::size_t i = 0; i < 4; ++i) {
      control[i] = convert(cubic[i]);
      reference[i] = Vec2<double>{{cubic[i][0], cubic[i][1]}};
    }
    const auto curve = Bezier<S, 2, 7>::create(control).value();
    const auto exact = Bezier<double, 2, 7>::create(reference).value();
    for (int k = points.empty() ? 0 : 1; k <= samples_per_segment; ++k) {
      const double t = static_cast<double>(k) / samples_per_segment;
      const auto p = to_doubles(curve.point_at(convert({t, 0})[0]));
      const auto q = exact.point_at(t);
      max_difference_to_double = std::fmax(max_difference_to_double, std::hypot(p[0] - q[0], p[1] - q[1]));
      points.push_back(p);
    }
  }
  // Close with an exact semicircle (rational cubic) from (160,60) back towards (0,60).
  const auto arc = circular_arc<double>(Vec2<double>{{80, 60}}, Vec2<double>{{160, 60}}, Vec2<double>{{0, 60}},
                                        ArcDirection::CounterClockwise, 1e-9);
  if (!arc) throw std::runtime_error(std::string("demo arc: ") + std::string(describe(arc.error())));
  for (int k = 1; k <= samples_per_segment * 2; ++k) {
    const auto p = arc.value().point_at(static_cast<double>(k) / (samples_per_segment * 2));
    points.push_back({p[0], p[1]});
  }
  return points;
}

void run_demo(const DemoOptions& options) {
  std::filesystem::create_directories(options.out);
  double fixed_difference = 0;
  double double_difference = 0;
  const auto fixed_points = sample_path<Q16_16>(options.samples_per_segment, fixed_difference);
  const auto double_points = sample_path<double>(options.samples_per_segment, double_difference);

  const std::string csv_path = options.out + "/demo_points.csv";
  std::ofstream csv(csv_path);
  if (!csv) throw std::runtime_error("cannot write " + csv_path);
  csv << "x,y\n";
  csv.precision(10);
  for (const auto& p : fixed_points) csv << p[0] << "," << p[1] << "\n";

  const std::string svg_path = options.out + "/demo_path.svg";
  write_svg_plot(svg_path, {PlotPolyline{fixed_points, "#1f77b4", false}}, "curvestep demo: cubic Beziers + exact arc (Q16.16)");

  std::cout << "curvestep demo\n"
            << "  segments:            3 cubic Bezier + 1 rational arc\n"
            << "  points (Q16.16):     " << fixed_points.size() << "\n"
            << "  max |Q16.16-double|: " << fixed_difference * 1000.0 << " um\n"
            << "  wrote " << csv_path << "\n"
            << "  wrote " << svg_path << "\n";
}

}  // namespace

namespace {

void add_demo_command(CLI::App& app) {
  auto options = std::make_shared<DemoOptions>();
  auto* demo = app.add_subcommand("demo", "Run the bundled demo end to end and write its outputs");
  demo->add_option("--out", options->out, "Output folder")->capture_default_str();
  demo->add_option("--samples", options->samples_per_segment, "Samples per segment")->check(CLI::Range(2, 100000))->capture_default_str();
  demo->callback([options] { run_demo(*options); });
}

const RegisterCommand registered{90, add_demo_command};

}  // namespace

}  // namespace curvestep::host
