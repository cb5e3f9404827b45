#pragma once
// Named time series sampled from a Simulation (wall force and torque, energies, bed height, or
// any custom quantity). Call record() from a run_until callback.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "demfit/dem_core/vec3.hpp"

namespace demfit::dem_core {

class Simulation;

struct TimeSeries {
  std::string name{};
  std::string unit{};            ///< e.g. "N", "N_m", "J", "m" (used in the CSV header)
  std::vector<double> values{};  ///< one per record() call
};

class ProbeRecorder {
 public:
  using Sampler = std::function<double(const Simulation&)>;

  /// Component along `direction` (normalised) of the force of the particles on wall i [N].
  void add_wall_force(const std::string& name, std::size_t wall, const Vec3& direction);
  /// Torque of the particles on wall i about its torque axis [N·m].
  void add_wall_torque(const std::string& name, std::size_t wall);
  void add_kinetic_energy(const std::string& name = "kinetic_energy");  ///< [J]
  void add_elastic_energy(const std::string& name = "elastic_energy");  ///< [J]
  /// Bed height along up [m] (see bed_height in packing.hpp).
  void add_bed_height(const std::string& name, const Vec3& up, double top_fraction = 0.05);
  void add(const std::string& name, const std::string& unit, Sampler sampler);

  /// Append the current time and one value per probe.
  void record(const Simulation& simulation);

  [[nodiscard]] const std::vector<double>& times() const { return times_; }  ///< [s]
  [[nodiscard]] const std::vector<TimeSeries>& series() const { return series_; }
  /// Series by name; throws std::runtime_error if unknown.
  [[nodiscard]] const TimeSeries& get(const std::string& name) const;
  /// CSV: header "time_s,<name>_<unit>,...", one row per record.
  void write_csv(const std::string& path) const;

 private:
  std::vector<double> times_{};
  std::vector<TimeSeries> series_{};
  std::vector<Sampler> samplers_{};
};

}  // namespace demfit::dem_core
