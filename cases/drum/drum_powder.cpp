// Drum fill (docs/spec.md 2.2, paper section 3): the powder of the case (fill amount rule, Table 2 coarse
// graining, size distribution) packed in the lower part of the drum and densified under gravity;
// the result is cached by fill_key. Frame: drum axis = z, gravity -y.
#include "drum_powder.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <random>
#include <stdexcept>

#include "dem_setup.hpp"
#include "demfit/cases/case_registry.hpp"
#include "demfit/cases/drum_fill.hpp"
#include "demfit/dem_core/packing.hpp"

namespace demfit::cases::detail {
namespace {

using dem_core::Vec3;

double drum_volume(const DrumSpec& d) { return std::numbers::pi * 0.25 * d.diameter * d.diameter * d.length; }

// Original (s = 1) particle count N0 of the fill amount (see FillBy): bulk volumes hold
// phi V_bulk of solid, N0 = solid / E[v].
double original_count(const CaseSpec& spec, double mean_volume) {
  const DrumSpec& d = spec.drum;
  switch (d.fill_by) {
    case FillBy::fill_fraction:
      return d.volume_fraction * d.fill_fraction * drum_volume(d) / mean_volume;
    case FillBy::fill_volume:
      return d.volume_fraction * d.fill_volume_ml * 1e-6 / mean_volume;
    case FillBy::particle_count:
      return static_cast<double>(d.particle_count);
    case FillBy::fill_mass:
      return d.fill_mass / (spec.material.density * mean_volume);
  }
  return 0.0;
}

}  // namespace

// Table 2 applied to the drum fill: the original powder's solid volume is phi times the bulk
// fill (fill_fraction of the drum volume); the coarse model carries its Table 2 total mass.
Powder powder_of(const CaseSpec& spec) {
  const DrumSpec& d = spec.drum;
  Powder p;
  if (!d.size_distribution.enabled() && d.fill_by == FillBy::fill_fraction) {
    // The paper's drum, computed exactly as before the general drum existed.
    p.original_total_mass = spec.material.density * d.volume_fraction * d.fill_fraction * drum_volume(d);
    p.particle = coarse_grain(d.coarse_graining, d.scale_factor, d.volume_fraction,
                              {spec.material.radius, spec.material.density});
    p.count = coarse_particle_count(p.particle, p.original_total_mass);
    p.original_count = p.original_total_mass / (spec.material.density * sphere_volume(spec.material.radius));
    p.bulk_fraction = d.fill_fraction;
    if (p.count < 1)
      throw std::runtime_error("drum: the fill holds less than one coarse particle: lower drum.scale_factor");
    return p;
  }
  const SizeDistributionSpec& sizes = d.size_distribution;
  const double mean_volume = sizes.enabled() ? sizes.mean_volume() : sphere_volume(spec.material.radius);
  p.original_count = original_count(spec, mean_volume);
  p.original_total_mass = spec.material.density * p.original_count * mean_volume;
  p.bulk_fraction = p.original_count * mean_volume / (d.volume_fraction * drum_volume(d));
  if (!sizes.enabled()) {
    p.particle = coarse_grain(d.coarse_graining, d.scale_factor, d.volume_fraction,
                              {spec.material.radius, spec.material.density});
    p.count = coarse_particle_count(p.particle, p.original_total_mass);
  } else {
    // Every size of the distribution is coarse-grained alike (Table 2 with r0 = 1 gives the
    // radius factor); SCG count = N0 / s^3, CVF phi N0 / s^3 (the Table 2 total mass).
    const CoarseParticle unit =
        coarse_grain(d.coarse_graining, d.scale_factor, d.volume_fraction, {1.0, spec.material.density});
    p.count =
        std::llround(unit.total_mass_factor * p.original_count / (d.scale_factor * d.scale_factor * d.scale_factor));
    if (p.count >= 1) {
      p.radii = sizes.sample_radii(static_cast<std::size_t>(p.count), static_cast<std::uint64_t>(d.fill_seed));
      for (double& r : p.radii) r *= unit.radius;
    }
    p.particle = coarse_grain(d.coarse_graining, d.scale_factor, d.volume_fraction,
                              {0.5 * sizes.min_diameter(), spec.material.density});
  }
  if (p.count < 1)
    throw std::runtime_error(
        "drum: the fill holds less than one coarse particle: lower drum.scale_factor or raise the fill");
  return p;
}

dem_core::Material powder_material(const CaseSpec& spec, const Powder& powder) {
  dem_core::Material m = to_material(spec.material);
  m.density = powder.particle.density;
  return m;
}

// Drum shell and end walls, all rotating about the z axis at `omega` [rad/s]; returns the first
// wall index (three walls: shell, end at z = 0, end at z = length).
std::size_t add_drum(dem_core::Simulation& sim, const CaseSpec& spec, double omega) {
  const double rd = 0.5 * spec.drum.diameter, len = spec.drum.length;
  const auto& contact = spec.wall;
  const dem_core::RotatingMotion motion{{0, 0, 0}, {0, 0, 1}, omega};
  const dem_core::Axis axis{{0, 0, 0}, {0, 0, 1}};
  const std::size_t first =
      sim.add_wall({dem_core::CylinderGeometry{{0, 0, 0}, {0, 0, 1}, rd, len}, motion, contact, axis, "shell"});
  sim.add_wall({dem_core::DiskGeometry{{0, 0, 0}, {0, 0, 1}, rd}, motion, contact, axis, "end_front"});
  sim.add_wall({dem_core::DiskGeometry{{0, 0, len}, {0, 0, -1}, rd}, motion, contact, axis, "end_back"});
  return first;
}

// to_key_json: effects at their off values leave the key (and so the cached fill) as before them.
// wall_mesh is left out: the fill is packed and settled in the analytic drum in every case (the
// mesh replaces the walls of the rotation stage only), so a meshed drum starts from the same fill.
nlohmann::json fill_key(const CaseSpec& spec) {
  return detail::fill_key_of(spec, "drum",
                             {"rpm", "duration", "torque_interval", "surface_window", "surface_snapshots",
                              "surface_points", "image", "wall_mesh"});
}

namespace {

// Largest count the random fallback places (see pack_and_densify).
constexpr long long kMaxRandomPlacement = 20000;

// Fallback when the lattice cannot hold the count (coarse particles only a few diameters shorter
// than the drum length): random sequential addition in the whole drum, seeded, no overlaps.
// With a radius spread s the radii are uniform in [R(1-s), R(1+s)] (a second seeded stream, so
// the monodisperse sequence is unchanged) and the target is the solid volume of `count` spheres.
// Size distribution: the sampled radii, largest first (small ones fill the gaps left), each at
// the first free random position inside the drum for its own radius (at most 200000 tries
// each), seeded by the fill seed.
// Adds the sphere (c, r) to the packing when it overlaps no sphere placed so far (0.01 % margin on
// the squared contact distance); returns whether it was placed.
bool place_if_free(dem_core::Packing& packing, const Vec3& c, double r) {
  for (std::size_t k = 0; k < packing.centers.size(); ++k) {
    const double contact = (packing.radii[k] + r) * (packing.radii[k] + r);
    if (dem_core::norm2(packing.centers[k] - c) < contact * 1.0001) return false;
  }
  packing.centers.push_back(c);
  packing.radii.push_back(r);
  packing.solid_volume += sphere_volume(r);
  return true;
}

std::optional<dem_core::Packing> random_packing_of_radii(const CaseSpec& spec, std::vector<double> radii) {
  std::stable_sort(radii.begin(), radii.end(), std::greater<>());
  std::mt19937_64 engine(static_cast<std::uint64_t>(spec.drum.fill_seed));
  auto uniform = [&engine] { return static_cast<double>(engine() >> 11) * 0x1.0p-53; };
  dem_core::Packing packing;
  for (const double r : radii) {
    const double reach = 0.5 * spec.drum.diameter - r;
    if (reach <= 0.0 || spec.drum.length < 2.0 * r) return std::nullopt;
    bool placed = false;
    for (int attempt = 0; attempt < 200000 && !placed; ++attempt) {
      const Vec3 c{(2.0 * uniform() - 1.0) * reach, (2.0 * uniform() - 1.0) * reach,
                   r + uniform() * (spec.drum.length - 2.0 * r)};
      if (c.x * c.x + c.y * c.y > reach * reach) continue;
      placed = place_if_free(packing, c, r);
    }
    if (!placed) return std::nullopt;
  }
  return packing;
}

std::optional<dem_core::Packing> random_packing(const CaseSpec& spec, const Powder& powder) {
  if (!powder.radii.empty()) return random_packing_of_radii(spec, powder.radii);
  const double spread = spec.material.radius_spread;
  const double r_max = powder.particle.radius * (1.0 + spread);
  const double reach = 0.5 * spec.drum.diameter - r_max;
  if (reach <= 0.0 || spec.drum.length < 2.0 * r_max) return std::nullopt;
  std::mt19937_64 engine(static_cast<std::uint64_t>(spec.drum.fill_seed));
  std::mt19937_64 size_engine(static_cast<std::uint64_t>(spec.drum.fill_seed) + 0x9e3779b97f4a7c15ULL);
  auto uniform = [&engine] { return static_cast<double>(engine() >> 11) * 0x1.0p-53; };
  const double target = static_cast<double>(powder.count) * sphere_volume(powder.particle.radius);
  auto done = [&](const dem_core::Packing& p) {
    return spread > 0.0 ? p.solid_volume >= target : static_cast<long long>(p.centers.size()) >= powder.count;
  };
  dem_core::Packing packing;
  double r = powder.particle.radius;
  bool next_radius = spread > 0.0;  // a new radius for the first sphere and after each placement
  for (long long attempt = 0; attempt < 2000000 && !done(packing); ++attempt) {
    if (next_radius) {
      r = powder.particle.radius * (1.0 + spread * (2.0 * static_cast<double>(size_engine() >> 11) * 0x1.0p-53 - 1.0));
      next_radius = false;
    }
    const Vec3 c{(2.0 * uniform() - 1.0) * reach, (2.0 * uniform() - 1.0) * reach,
                 r_max + uniform() * (spec.drum.length - 2.0 * r_max)};
    if (c.x * c.x + c.y * c.y > reach * reach) continue;
    if (!place_if_free(packing, c, r)) continue;
    next_radius = spread > 0.0;
  }
  if (!done(packing)) return std::nullopt;
  return packing;
}

}  // namespace

// Packed generation in the lower part of the drum, enlarged until the lattice holds the count
// (the paper's "extending the volume of the packed region"), then frictionless densification
// followed by a short settle with friction (dem_core::settle).
Fill pack_and_densify(const CaseSpec& spec, const CaseRunOptions& options) {
  const Powder powder = powder_of(spec);
  dem_core::SimulationSettings settings = simulation_settings(spec);
  settings.gravity = {0.0, -9.81, 0.0};
  settings.threads = options.threads;
  settings.time_step_factor = kFillTimeStepFactor;
  dem_core::Simulation sim(settings);
  sim.add_material(powder_material(spec, powder));
  const double rd = 0.5 * spec.drum.diameter;
  dem_core::PackingRequest request;
  request.radius_min = request.radius_max = powder.particle.radius;
  if (!powder.radii.empty()) {
    // Size distribution: the sampled radii on an fcc lattice sized for the largest one (a cubic
    // one cannot hold the GranuDrum fill: its sites are sized by the largest sphere).
    request.radii = powder.radii;
    request.lattice = dem_core::PackingRequest::Lattice::fcc;
  } else if (spec.material.radius_spread > 0.0) {
    // Polydisperse: the coarse-grained radius gets the same relative spread; the packing keeps
    // the solid volume (hence the total mass of Table 2 and the fill's volume fraction).
    request.radius_spread = spec.material.radius_spread;
    request.solid_volume = static_cast<double>(powder.count) * sphere_volume(powder.particle.radius);
  } else {
    request.count = static_cast<std::size_t>(powder.count);
  }
  request.seed = static_cast<std::uint64_t>(spec.drum.fill_seed);
  request.up = {0, 1, 0};
  std::optional<dem_core::Packing> packing;
  std::string last_error;
  for (double gap : {0.2, 0.1, 0.03}) {
    for (double fraction = std::min(0.9, 1.2 * powder.bulk_fraction); fraction <= 0.995 && !packing; fraction += 0.05) {
      request.gap = gap;
      request.region = dem_core::DrumSegmentRegion{
          {0, 0, 0}, {0, 0, 1}, rd, spec.drum.length, {0, 1, 0}, dem_core::drum_fill_height(rd, fraction)};
      try {
        packing = dem_core::generate_packing(request);
      } catch (const std::exception& e) { last_error = e.what(); }
    }
    if (packing) break;
  }
  // The random fallback checks each try against every sphere placed so far, so its cost grows with
  // the square of the count (hours, silently, for a 2 m drum of 1 mm spheres): bounded, and refused
  // with the figure above the bound.
  if (!packing && powder.count > kMaxRandomPlacement)
    throw std::runtime_error("drum: " + std::to_string(powder.count) +
                             " particles do not fit the packed lattice, and random placement is limited to " +
                             std::to_string(kMaxRandomPlacement) +
                             " particles (its cost grows with the square of the count): raise drum.scale_factor, "
                             "lower the fill or enlarge the drum");
  if (!packing) packing = random_packing(spec, powder);
  if (!packing)
    throw std::runtime_error("drum: cannot place " + std::to_string(powder.count) + " particles: " + last_error);
  dem_core::add_packing(sim, *packing);
  add_drum(sim, spec, 0.0);
  if (options.progress) options.progress("densify", 0.0, spec.drum.densify_time);
  dem_core::SettleOptions settle_options;
  settle_options.max_time = spec.drum.densify_time;
  settle_options.frictionless = true;
  if (options.progress)
    settle_options.progress = [&](double elapsed, double end) { options.progress("densify", elapsed, end); };
  dem_core::settle(sim, settle_options);
  if (options.progress) options.progress("densify", spec.drum.densify_time, spec.drum.densify_time);
  return detail::fill_of(sim);
}

}  // namespace demfit::cases::detail

namespace demfit::cases {

DrumFillAmount drum_fill_amount(const CaseSpec& spec) {
  if (spec.kind != CaseKind::rotary_drum) throw std::runtime_error("drum_fill_amount: the case is not a rotary_drum");
  const detail::Powder powder = detail::powder_of(spec);
  return {powder.original_count, powder.count, powder.original_total_mass};
}

}  // namespace demfit::cases
