#pragma once
// Multi-column curve CSV output with '#' comment lines (read back by identify::read_curve_csv,
// which skips comments). Header names carry units ("volume_cm3,pressure_MPa").
#include <filesystem>
#include <string>
#include <vector>

#include "demfit/identify/model.hpp"

namespace demfit::cases {

struct CurveTable {
  std::vector<std::string> comments;        // written as "# <line>" before the header
  std::vector<std::string> columns;         // header names with units
  std::vector<std::vector<double>> values;  // one vector per column, equal lengths
};

// Writes the table (17 significant digits). Throws naming the file on I/O failure.
void write_curve_table(const std::filesystem::path& path, const CurveTable& table);

// A single curve as a two-column table.
CurveTable curve_table(const identify::Curve& curve, std::vector<std::string> comments = {});

}  // namespace demfit::cases
