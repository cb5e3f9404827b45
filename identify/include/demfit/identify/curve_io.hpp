#pragma once
// Curve CSV files: a header naming each column with its unit (e.g. "volume_cm3,pressure_MPa"),
// then one row of numbers per point. Comment lines starting with '#' are skipped.
#include <cstddef>
#include <filesystem>
#include <istream>
#include <string>

#include "demfit/identify/model.hpp"

namespace demfit::identify {

// Documented limits (docs/study_format.md): a curve file of at most kMaxCurveFileBytes bytes,
// kMaxCurvePoints points and kMaxCurveLineBytes per line. A UTF-8 byte-order mark is accepted.
inline constexpr std::size_t kMaxCurveFileBytes = 64u << 20;  // 64 MiB
inline constexpr std::size_t kMaxCurvePoints = 100000;
inline constexpr std::size_t kMaxCurveLineBytes = 4096;

// Reads columns x_column and y_column (header names) from a CSV file. Throws std::runtime_error
// naming the file and line on a missing column, a non-number or fewer than 2 points.
Curve read_curve_csv(const std::filesystem::path& path, const std::string& x_column, const std::string& y_column);
// The same from a stream; `path` names the source in errors.
Curve parse_curve_csv(std::istream& in, const std::filesystem::path& path, const std::string& x_column,
                      const std::string& y_column);
// Writes "x_label,y_label" then the points (17 significant digits), to a temporary file that
// is renamed over `path` (never a half-written file).
void write_curve_csv(const std::filesystem::path& path, const Curve& curve);

}  // namespace demfit::identify
