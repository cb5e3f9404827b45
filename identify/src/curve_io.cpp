// Curve CSV reading/writing (docs/spec.md 4: header names each column with its unit).
#include "demfit/identify/curve_io.hpp"

#include <charconv>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "demfit/identify/safe_output.hpp"

namespace demfit::identify {
namespace {

std::string trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r\n\"");
  if (begin == std::string::npos) return {};
  const auto end = text.find_last_not_of(" \t\r\n\"");
  return text.substr(begin, end - begin + 1);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(trim(field));
  return fields;
}

std::size_t column_index(const std::vector<std::string>& header, const std::string& name,
                         const std::filesystem::path& path) {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return i;
  std::string known;
  for (const auto& h : header) known += (known.empty() ? "" : ", ") + h;
  if (known.size() > 200) known = known.substr(0, 200) + "...";
  for (char& c : known)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  // A spreadsheet export with another separator (';' or tab, often with decimal commas) reads as
  // one column: say so, since the printed header then looks right.
  std::string hint;
  if (header.size() == 1 && header[0].find_first_of(";\t") != std::string::npos)
    hint = "; the columns are separated by ';' or tabs: save the file with comma separators and decimal points";
  throw std::runtime_error("curve file " + quote_path(path) + ": no column '" + name + "'; the header has: " + known +
                           hint);
}

double parse_number(const std::string& text, const std::filesystem::path& path, int line) {
  double value = 0.0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (!text.empty() && *first == '+') ++first;
  const auto result = std::from_chars(first, last, value);
  if (result.ec != std::errc() || result.ptr != last) {
    std::string shown = text.size() > 40 ? text.substr(0, 40) + "..." : text;
    for (char& c : shown)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    throw std::runtime_error("curve file " + quote_path(path) + " line " + std::to_string(line) + ": '" + shown +
                             "' is not a number; fix the value");
  }
  return value;
}

}  // namespace

Curve parse_curve_csv(std::istream& in, const std::filesystem::path& path, const std::string& x_column,
                      const std::string& y_column) {
  Curve curve{x_column, y_column, {}, {}};
  std::string line;
  std::vector<std::string> header;
  std::size_t ix = 0, iy = 0;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    // Excel writes a UTF-8 byte-order mark before the header: accept it.
    if (line_number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
    if (line.size() > kMaxCurveLineBytes)
      throw std::runtime_error("curve file " + quote_path(path) + " line " + std::to_string(line_number) +
                               ": longer than " + std::to_string(kMaxCurveLineBytes) +
                               " bytes; is this a curve CSV file?");
    const std::string content = trim(line);
    if (content.empty() || content[0] == '#') continue;
    const auto fields = split_fields(content);
    if (header.empty()) {
      header = fields;
      ix = column_index(header, x_column, path);
      iy = column_index(header, y_column, path);
      continue;
    }
    if (fields.size() != header.size())
      throw std::runtime_error("curve file " + quote_path(path) + " line " + std::to_string(line_number) + ": " +
                               std::to_string(fields.size()) + " fields, header has " + std::to_string(header.size()) +
                               (fields.size() > header.size() ? "; a decimal comma splits a number in two: use points"
                                                              : "; give one value per column"));
    if (curve.x.size() >= kMaxCurvePoints)
      throw std::runtime_error("curve file " + quote_path(path) + ": more than " + std::to_string(kMaxCurvePoints) +
                               " points; thin the curve (a few hundred points describe it)");
    curve.x.push_back(parse_number(fields[ix], path, line_number));
    curve.y.push_back(parse_number(fields[iy], path, line_number));
  }
  if (header.empty())
    throw std::runtime_error(
        "curve file " + quote_path(path) +
        ": no header line; the first line names the columns with units, e.g. volume_cm3,pressure_MPa");
  if (curve.x.size() < 2)
    throw std::runtime_error("curve file " + quote_path(path) + ": fewer than 2 points; a curve needs at least 2");
  return curve;
}

Curve read_curve_csv(const std::filesystem::path& path, const std::string& x_column, const std::string& y_column) {
  // A regular file of at most kMaxCurveFileBytes: a device such as /dev/zero is refused unread.
  std::istringstream in(read_input_file(path, kMaxCurveFileBytes, "curve file " + quote_path(path)));
  return parse_curve_csv(in, path, x_column, y_column);
}

void write_curve_csv(const std::filesystem::path& path, const Curve& curve) {
  if (curve.x.size() != curve.y.size())
    throw std::runtime_error("write_curve_csv: x and y sizes differ for " + quote_path(path));
  std::string text = curve.x_label + "," + curve.y_label + "\n";
  char buffer[64];
  for (std::size_t i = 0; i < curve.x.size(); ++i) {
    std::snprintf(buffer, sizeof buffer, "%.17g,%.17g\n", curve.x[i], curve.y[i]);
    text += buffer;
  }
  write_file_atomically(path, text);
}

}  // namespace demfit::identify
