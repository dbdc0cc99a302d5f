// SPDX-License-Identifier: MIT
// CSV output of points.
#include <curvestep/host/csv.hpp>

#include <array>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <charconv>
#include <system_error>

namespace curvestep::host {

std::string format_number(double value) {
  if (value == 0) return "0";  // also turns -0 into 0
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  if (result.ec != std::errc{}) return "nan";
  return std::string(buffer.data(), result.ptr);
}

void write_points_csv(std::ostream& out, std::span<const MachinePoint> points) {
  out << "x,y,z\n";
  for (const auto& p : points) {
    out << format_number(p[0]) << ',' << format_number(p[1]) << ',' << format_number(p[2]) << '\n';
  }
}

void write_output(const std::string& path, const std::function<void(std::ostream&)>& write) {
  if (path.empty()) {
    write(std::cout);
    std::cout.flush();
    return;
  }
  std::ofstream file(path);
  if (!file) throw std::runtime_error(path + ": cannot open for writing");
  write(file);
  file.flush();
  if (!file) throw std::runtime_error(path + ": write failed");
}

}  // namespace curvestep::host
