// Curve CSV output (see curve_table.hpp).
#include "demfit/cases/curve_table.hpp"

#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "demfit/identify/safe_output.hpp"

namespace demfit::cases {

void write_curve_table(const std::filesystem::path& path, const CurveTable& table) {
  if (table.columns.size() != table.values.size()) {
    throw std::runtime_error("curve table '" + path.string() + "': column names and data differ in count");
  }
  // Built in memory, then written through the one atomic writer: a full disk or a
  // planted link never leaves a half-written or redirected curve.
  std::ostringstream out;
  for (const std::string& line : table.comments) out << "# " << line << '\n';
  for (std::size_t c = 0; c < table.columns.size(); ++c) out << (c ? "," : "") << table.columns[c];
  out << '\n' << std::setprecision(17);
  const std::size_t rows = table.values.empty() ? 0 : table.values.front().size();
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < table.values.size(); ++c) out << (c ? "," : "") << table.values[c].at(r);
    out << '\n';
  }
  identify::write_file_atomically(path, out.str());
}

CurveTable curve_table(const identify::Curve& curve, std::vector<std::string> comments) {
  return CurveTable{std::move(comments), {curve.x_label, curve.y_label}, {curve.x, curve.y}};
}

}  // namespace demfit::cases
