// The "drum" section of a case file (docs/spec.md 2.2 and the general drum): its plain fields are
// rows of kDrumFields (section_fields.hpp); the fill amount (exactly one of four keys), the
// coarse-graining model, the size distribution and the image options need their own code.
#include <array>
#include <numbers>
#include <stdexcept>

#include "demfit/cases/parameter_table.hpp"
#include "demfit/cases/section_fields.hpp"
#include "drum_case.hpp"

namespace demfit::cases::detail {
namespace {

using nlohmann::json;
using Field = SectionField<DrumSpec>;

// Units: see DrumSpec (case_spec.hpp) and docs/case_format.md.
const std::array<Field, 12> kDrumFields{{
    {"diameter", &DrumSpec::diameter, Sign::positive},
    {"length", &DrumSpec::length, Sign::positive},
    {"rpm", &DrumSpec::rpm},
    {"duration", &DrumSpec::duration, Sign::positive},
    {"volume_fraction", &DrumSpec::volume_fraction, Sign::any, 0.05, 1.0},
    {"scale_factor", &DrumSpec::scale_factor, Sign::any, 1.0, 16.0},
    {"fill_seed", &DrumSpec::fill_seed, Sign::any, -kUnbounded, kUnbounded, 0},
    {"densify_time", &DrumSpec::densify_time, Sign::positive},
    {"torque_interval", &DrumSpec::torque_interval, Sign::positive},
    {"surface_window", &DrumSpec::surface_window, Sign::non_negative},
    {"surface_snapshots", &DrumSpec::surface_snapshots, Sign::any, -kUnbounded, kUnbounded, 1},
    {"surface_points", &DrumSpec::surface_points, Sign::any, -kUnbounded, kUnbounded, 2},
}};

// Upper limits of the drum's count fields (docs/cases.md "Limits").
constexpr long long kMaxSurfaceSnapshots = 1000;
constexpr long long kMaxProfilePoints = 100000;
constexpr long long kMaxImagePixels = 8192;

DrumImageSpec parse_drum_image(const json& j) {
  const char* p = "drum.image";
  require_known_keys(j, p, {"pixels", "margin", "points"});
  DrumImageSpec image;
  image.enabled = true;
  image.pixels = read_integer(j, p, "pixels", image.pixels, 32);
  image.margin = read_bounded(j, p, "margin", image.margin, 0.0, 0.95);
  image.points = read_integer(j, p, "points", image.points, 2);
  if (image.pixels > kMaxImagePixels)
    throw std::runtime_error("'drum.image.pixels' must be at most " + std::to_string(kMaxImagePixels) +
                             " (pixels across the drum)");
  if (image.points > kMaxProfilePoints)
    throw std::runtime_error("'drum.image.points' must be at most " + std::to_string(kMaxProfilePoints));
  return image;
}

// Exactly one fill amount (fill_fraction when none is given; see FillBy).
void parse_fill_amount(const json& j, DrumSpec& s) {
  const char* p = "drum";
  int given = 0;
  for (const char* k : kDrumFillKeys) given += j.contains(k) ? 1 : 0;
  if (given > 1)
    throw std::runtime_error("'drum': give exactly one of fill_fraction, fill_volume_ml, particle_count or fill_mass");
  s.fill_fraction = read_bounded(j, p, "fill_fraction", s.fill_fraction, 0.01, 0.9);
  if (j.contains("fill_volume_ml")) {
    s.fill_by = FillBy::fill_volume;
    s.fill_volume_ml = read_parameter(j, p, "fill_volume_ml", 0.0);
  } else if (j.contains("particle_count")) {
    s.fill_by = FillBy::particle_count;
    s.particle_count =
        read_integer(j, p, "particle_count", 0, static_cast<long long>(find_parameter("particle_count")->valid.lower));
  } else if (j.contains("fill_mass")) {
    s.fill_by = FillBy::fill_mass;
    s.fill_mass = read_number(j, p, "fill_mass", 0.0, Sign::positive);
  } else if (j.contains("fill_fraction")) {
    s.fill_by = FillBy::fill_fraction;
  }
}

DrumSpec parse_drum(const json& j, DrumSpec s, const std::filesystem::path& base_dir) {
  const char* p = "drum";
  std::vector<std::string> special(std::begin(kDrumFillKeys), std::end(kDrumFillKeys));
  special.insert(special.end(), {"coarse_graining", "size_distribution", "image", "wall_mesh"});
  require_known_keys(j, p, section_keys<DrumSpec>(kDrumFields, special));
  read_section_fields<DrumSpec>(j, p, kDrumFields, s);
  parse_fill_amount(j, s);
  const std::string cg = read_string(j, p, "coarse_graining", to_string(s.coarse_graining));
  try {
    s.coarse_graining = parse_coarse_graining(cg);
  } catch (const std::exception&) {
    throw std::runtime_error("'drum.coarse_graining' must be \"scg\" or \"cvf\" (got \"" + cg + "\")");
  }
  if (s.surface_window > s.duration) {
    throw std::runtime_error("'drum.surface_window' must not exceed 'drum.duration'");
  }
  // Counts bounded so that no input allocates gigabytes (docs/cases.md "Limits").
  if (s.torque_interval > s.duration)
    throw std::runtime_error(
        "'drum.torque_interval' must not exceed 'drum.duration': give a sampling interval shorter than the run, "
        "e.g. 0.01");
  if (s.surface_snapshots > kMaxSurfaceSnapshots)
    throw std::runtime_error("'drum.surface_snapshots' must be at most " + std::to_string(kMaxSurfaceSnapshots));
  if (s.surface_points > kMaxProfilePoints)
    throw std::runtime_error("'drum.surface_points' must be at most " + std::to_string(kMaxProfilePoints));
  if (j.contains("size_distribution"))
    s.size_distribution =
        parse_size_distribution(child_object(j, p, "size_distribution"), "drum.size_distribution", base_dir);
  if (j.contains("image")) s.image = parse_drum_image(child_object(j, p, "image"));
  if (j.contains("wall_mesh"))
    s.wall_mesh = parse_drum_wall_mesh(child_object(j, p, "wall_mesh"), s.diameter, s.length, base_dir);
  if (s.fill_by == FillBy::fill_volume) {
    const double drum_ml = std::numbers::pi * 0.25 * s.diameter * s.diameter * s.length * 1e6;
    if (s.fill_volume_ml > 0.9 * drum_ml)
      throw std::runtime_error("'drum.fill_volume_ml' = " + std::to_string(s.fill_volume_ml) +
                               " exceeds 90 % of the drum volume (" + std::to_string(drum_ml) + " mL): lower it");
  }
  return s;
}

}  // namespace

void parse_drum_section(const json& document, CaseSpec& spec, const std::filesystem::path& base_dir) {
  spec.drum = parse_drum(child_object(document, "", "drum"), spec.drum, base_dir);
  if (!spec.drum.size_distribution.enabled()) return;
  if (child_object(document, "", "particle").contains("radius"))
    throw std::runtime_error(
        "'particle.radius' cannot be given with 'drum.size_distribution': the distribution sets the sizes");
  if (spec.material.radius_spread != 0.0)
    throw std::runtime_error("'particle.radius_spread' cannot be combined with 'drum.size_distribution'");
  spec.material.radius = 0.5 * spec.drum.size_distribution.min_diameter();  // smallest size (time-step checks)
}

json drum_section_json(const DrumSpec& d) {
  json j = json::object();
  write_section_fields<DrumSpec>(j, kDrumFields, d);
  j["coarse_graining"] = to_string(d.coarse_graining);
  // General-drum options appear only when used, so a paper drum keeps its old text.
  if (d.fill_by == FillBy::fill_fraction) j["fill_fraction"] = d.fill_fraction;
  if (d.fill_by == FillBy::fill_volume) j["fill_volume_ml"] = d.fill_volume_ml;
  if (d.fill_by == FillBy::particle_count) j["particle_count"] = d.particle_count;
  if (d.fill_by == FillBy::fill_mass) j["fill_mass"] = d.fill_mass;
  if (d.size_distribution.enabled()) j["size_distribution"] = to_json(d.size_distribution);
  if (d.image.enabled)
    j["image"] = {{"pixels", d.image.pixels}, {"margin", d.image.margin}, {"points", d.image.points}};
  if (d.wall_mesh.enabled()) j["wall_mesh"] = to_json(d.wall_mesh);
  return j;
}

}  // namespace demfit::cases::detail
