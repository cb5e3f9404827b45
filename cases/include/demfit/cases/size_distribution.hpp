#pragma once
// Particle size distribution of a drum fill: measured sizes from a CSV column, or
// size classes with number or mass fractions; lower/upper size cut-offs; deterministic sampling
// from the fill seed. Sizes are stored as sphere DIAMETERS in metres.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace demfit::cases {

struct SizeDistributionSpec {
  enum class Source { none, csv, classes };
  Source source = Source::none;
  // CSV: file as written in the case (relative paths resolve against the case file's folder),
  // column name, unit of the values ("m", "mm", "um"), and what the values are
  // ("sphere_diameter", "max_feret": a maximum Feret diameter taken as the sphere diameter,
  // the source's choice for near-spherical MCC pellets; "radius").
  std::string csv;
  std::string column;
  std::string unit = "m";
  std::string diameter_kind = "sphere_diameter";
  // Classes: class sizes in `unit` (as "diameter" or "radius" in the file) and their fractions,
  // by number ("number_fraction") or by mass ("mass_fraction"); fractions are normalised.
  bool classes_as_radius = false;
  std::vector<double> class_sizes;  // in `unit`, as written
  std::vector<double> class_fractions;
  bool mass_fractions = false;
  // Cut-offs in `unit` (of the same quantity as the sizes: diameter, or radius for radius data);
  // sizes below min_size or above max_size are dropped. 0 = no cut-off.
  double min_size = 0.0;
  double max_size = 0.0;

  // Resolved at parse time: the retained sphere diameters [m] (CSV: every row kept, in file
  // order; classes: one entry per class) with their number weights (CSV: 1 each).
  std::vector<double> diameters;
  std::vector<double> weights;

  bool enabled() const { return source != Source::none; }
  // Number-weighted mean sphere volume E[v] [m^3] of the retained sizes.
  double mean_volume() const;
  // Largest and smallest retained diameter [m].
  double max_diameter() const;
  double min_diameter() const;
  // `count` radii [m] drawn with replacement from the number distribution, deterministic in
  // `seed` (std::mt19937_64 with our own uniform mapping, platform-independent).
  std::vector<double> sample_radii(std::size_t count, std::uint64_t seed) const;
  // FNV-1a hash of the retained diameters and weights (fill cache key).
  std::uint64_t content_hash() const;
};

// Parses drum.size_distribution; `path` = dotted location for messages. Reads the CSV now
// (relative to base_dir): a missing file, missing column, or an empty, non-numeric, NaN or
// non-positive value is a one-line error naming the file and the row.
SizeDistributionSpec parse_size_distribution(const nlohmann::json& j, const std::string& path,
                                             const std::filesystem::path& base_dir);
nlohmann::json to_json(const SizeDistributionSpec& spec);

// Reads one numeric column of a CSV file (comma separated, first line = header, UTF-8 BOM and
// CRLF accepted). Values are returned as written. Errors name the file, row and the fix.
std::vector<double> read_csv_column(const std::filesystem::path& file, const std::string& column);

}  // namespace demfit::cases
