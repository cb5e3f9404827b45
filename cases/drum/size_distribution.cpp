// Size distributions of drum fills (see size_distribution.hpp).
#include "demfit/cases/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>

#include "demfit/cases/json_fields.hpp"

namespace demfit::cases {
namespace {

using nlohmann::json;

double unit_factor(const std::string& unit, const std::string& path) {
  if (unit == "m") return 1.0;
  if (unit == "mm") return 1e-3;
  if (unit == "um") return 1e-6;
  throw std::runtime_error("'" + path + ".unit' must be \"m\", \"mm\" or \"um\" (got \"" + unit + "\")");
}

std::vector<std::string> split_csv_line(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\"");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\"");
  return s.substr(b, e - b + 1);
}

std::vector<double> read_number_array(const json& j, const std::string& path, const char* key) {
  const json& a = j.at(key);
  const std::string name = path + "." + key;
  if (!a.is_array() || a.empty()) throw std::runtime_error("'" + name + "' must be a non-empty array of numbers");
  std::vector<double> out;
  for (const json& v : a) {
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0.0)
      throw std::runtime_error("'" + name + "' entries must be finite numbers >= 0");
    out.push_back(v.get<double>());
  }
  return out;
}

double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

std::vector<double> read_csv_column(const std::filesystem::path& file, const std::string& column) {
  std::ifstream in(file, std::ios::binary);
  const std::string name = file.string();
  if (!in)
    throw std::runtime_error("size CSV '" + name +
                             "' cannot be opened: check the path (relative paths start at the case file's folder)");
  std::string line;
  if (!std::getline(in, line))
    throw std::runtime_error("size CSV '" + name + "' is empty: it needs a header line and one size per row");
  if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 byte-order mark
  const std::vector<std::string> header = split_csv_line(line);
  std::size_t index = header.size();
  for (std::size_t k = 0; k < header.size(); ++k)
    if (trimmed(header[k]) == column) index = k;
  if (index == header.size())
    throw std::runtime_error("size CSV '" + name + "' has no column '" + column +
                             "' in its header line: set size_distribution.column");
  std::vector<double> values;
  long long row = 1;
  while (std::getline(in, line)) {
    ++row;
    if (trimmed(line == "\r" ? "" : line).empty()) continue;  // blank lines (e.g. at the end)
    const std::vector<std::string> cells = split_csv_line(line);
    const std::string cell = index < cells.size() ? trimmed(cells[index]) : "";
    const std::string where = "size CSV '" + name + "' row " + std::to_string(row) + " column '" + column + "'";
    if (cell.empty()) throw std::runtime_error(where + " is empty: every row needs a size (remove the row)");
    double v = 0.0;
    std::size_t used = 0;
    try {
      v = std::stod(cell, &used);
    } catch (const std::exception&) { used = 0; }
    if (used != cell.size())
      throw std::runtime_error(where + " = '" + cell + "' is not a number: fix or remove the row");
    if (!std::isfinite(v)) throw std::runtime_error(where + " = '" + cell + "' is not finite: fix or remove the row");
    if (v <= 0.0) throw std::runtime_error(where + " = " + cell + " must be > 0: fix or remove the row");
    values.push_back(v);
  }
  if (values.empty()) throw std::runtime_error("size CSV '" + name + "' has no data rows: it needs one size per row");
  return values;
}

SizeDistributionSpec parse_size_distribution(const json& j, const std::string& path,
                                             const std::filesystem::path& base_dir) {
  require_known_keys(j, path,
                     {"csv", "column", "unit", "diameter_kind", "diameter", "radius", "number_fraction",
                      "mass_fraction", "min_size", "max_size"});
  SizeDistributionSpec s;
  s.unit = read_string(j, path, "unit", s.unit);
  const double to_m = unit_factor(s.unit, path);
  s.min_size = read_number(j, path, "min_size", 0.0, Sign::non_negative);
  s.max_size = read_number(j, path, "max_size", 0.0, Sign::non_negative);
  std::vector<double> sizes, weights;  // in `unit`, of the quantity given
  bool radius = false;
  if (j.contains("csv")) {
    for (const char* k : {"diameter", "radius", "number_fraction", "mass_fraction"})
      if (j.contains(k))
        throw std::runtime_error("'" + path + "." + k + "' cannot be combined with '" + path +
                                 ".csv': give measured sizes or classes");
    s.source = SizeDistributionSpec::Source::csv;
    s.csv = read_string(j, path, "csv", "");
    if (!j.contains("column"))
      throw std::runtime_error("'" + path + ".column' is missing: name the CSV column holding the sizes");
    s.column = read_string(j, path, "column", "");
    s.diameter_kind = read_string(j, path, "diameter_kind", s.diameter_kind);
    if (s.diameter_kind != "sphere_diameter" && s.diameter_kind != "max_feret" && s.diameter_kind != "radius")
      throw std::runtime_error("'" + path +
                               ".diameter_kind' must be \"sphere_diameter\", \"max_feret\" or \"radius\" (got \"" +
                               s.diameter_kind + "\")");
    radius = s.diameter_kind == "radius";
    std::filesystem::path file(s.csv);
    if (file.is_relative()) file = base_dir / file;
    sizes = read_csv_column(file, s.column);
    weights.assign(sizes.size(), 1.0);
  } else {
    for (const char* k : {"column", "diameter_kind"})
      if (j.contains(k))
        throw std::runtime_error("'" + path + "." + k + "' applies to a CSV only: add '" + path + ".csv' or remove it");
    if (j.contains("diameter") == j.contains("radius"))
      throw std::runtime_error("'" + path + "' needs exactly one of 'csv', 'diameter' or 'radius' (class sizes)");
    if (j.contains("number_fraction") == j.contains("mass_fraction"))
      throw std::runtime_error("'" + path + "' needs exactly one of 'number_fraction' or 'mass_fraction'");
    s.source = SizeDistributionSpec::Source::classes;
    s.classes_as_radius = radius = j.contains("radius");
    s.class_sizes = read_number_array(j, path, radius ? "radius" : "diameter");
    s.mass_fractions = j.contains("mass_fraction");
    s.class_fractions = read_number_array(j, path, s.mass_fractions ? "mass_fraction" : "number_fraction");
    if (s.class_fractions.size() != s.class_sizes.size())
      throw std::runtime_error("'" + path + "': the fractions must have one entry per class size (" +
                               std::to_string(s.class_sizes.size()) + ")");
    for (double v : s.class_sizes)
      if (!(v > 0.0))
        throw std::runtime_error("'" + path + (radius ? ".radius" : ".diameter") + "' entries must be > 0");
    sizes = s.class_sizes;
    weights = s.class_fractions;
    // Mass fractions -> number fractions: n_i proportional to w_i / d_i^3.
    if (s.mass_fractions)
      for (std::size_t k = 0; k < sizes.size(); ++k) weights[k] /= sizes[k] * sizes[k] * sizes[k];
  }
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    if (sizes[k] < s.min_size || (s.max_size > 0.0 && sizes[k] > s.max_size) || weights[k] <= 0.0) continue;
    s.diameters.push_back(sizes[k] * to_m * (radius ? 2.0 : 1.0));
    s.weights.push_back(weights[k]);
  }
  if (s.diameters.empty())
    throw std::runtime_error("'" + path + "': no size is left between min_size and max_size: widen the cut-offs");
  return s;
}

json to_json(const SizeDistributionSpec& s) {
  json j;
  if (s.source == SizeDistributionSpec::Source::csv) {
    j = {{"csv", s.csv}, {"column", s.column}, {"unit", s.unit}, {"diameter_kind", s.diameter_kind}};
  } else {
    j = {{"unit", s.unit}};
    j[s.classes_as_radius ? "radius" : "diameter"] = s.class_sizes;
    j[s.mass_fractions ? "mass_fraction" : "number_fraction"] = s.class_fractions;
  }
  if (s.min_size > 0.0) j["min_size"] = s.min_size;
  if (s.max_size > 0.0) j["max_size"] = s.max_size;
  return j;
}

double SizeDistributionSpec::mean_volume() const {
  double total = 0.0, volume = 0.0;
  for (std::size_t k = 0; k < diameters.size(); ++k) {
    total += weights[k];
    volume += weights[k] * std::numbers::pi / 6.0 * diameters[k] * diameters[k] * diameters[k];
  }
  return volume / total;
}

double SizeDistributionSpec::max_diameter() const { return *std::max_element(diameters.begin(), diameters.end()); }
double SizeDistributionSpec::min_diameter() const { return *std::min_element(diameters.begin(), diameters.end()); }

std::vector<double> SizeDistributionSpec::sample_radii(std::size_t count, std::uint64_t seed) const {
  // Inverse-CDF sampling of the discrete number distribution (CSV rows have equal weights, so this
  // is resampling of the measured sizes with replacement).
  std::vector<double> cdf(weights.size());
  double sum = 0.0;
  for (std::size_t k = 0; k < weights.size(); ++k) cdf[k] = (sum += weights[k]);
  std::mt19937_64 rng(seed ^ 0x5DEECE66DULL);
  std::vector<double> radii(count);
  for (double& r : radii) {
    const double u = uniform01(rng) * sum;
    const auto k = static_cast<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin());
    r = 0.5 * diameters[std::min(k, diameters.size() - 1)];
  }
  return radii;
}

std::uint64_t SizeDistributionSpec::content_hash() const {
  std::uint64_t h = 1469598103934665603ULL;
  auto mix = [&h](double v) {
    unsigned char bytes[sizeof v];
    std::memcpy(bytes, &v, sizeof v);
    for (unsigned char b : bytes) h = (h ^ b) * 1099511628211ULL;
  };
  for (double d : diameters) mix(d);
  for (double w : weights) mix(w);
  return h;
}

}  // namespace demfit::cases
