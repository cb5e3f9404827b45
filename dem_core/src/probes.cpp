// Named time series sampled from a simulation.
#include "demfit/dem_core/probes.hpp"

#include <fstream>
#include <stdexcept>

#include "demfit/dem_core/packing.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "validation.hpp"

namespace demfit::dem_core {

void ProbeRecorder::add(const std::string& name, const std::string& unit, Sampler sampler) {
  if (name.empty()) throw std::runtime_error("probe name is empty; give every probe a name");
  for (const TimeSeries& s : series_)
    if (s.name == name) throw std::runtime_error("probe name '" + name + "' is used twice; names must be unique");
  if (!times_.empty()) throw std::runtime_error("probe '" + name + "' added after recording started; add probes first");
  series_.push_back({name, unit, {}});
  samplers_.push_back(std::move(sampler));
}

void ProbeRecorder::add_wall_force(const std::string& name, std::size_t wall, const Vec3& direction) {
  const Vec3 d = require_direction("probe '" + name + "' direction", direction);
  add(name, "N", [wall, d](const Simulation& s) { return dot(s.wall_force(wall), d); });
}

void ProbeRecorder::add_wall_torque(const std::string& name, std::size_t wall) {
  add(name, "N_m", [wall](const Simulation& s) { return s.wall_torque(wall); });
}

void ProbeRecorder::add_kinetic_energy(const std::string& name) {
  add(name, "J", [](const Simulation& s) { return s.kinetic_energy(); });
}

void ProbeRecorder::add_elastic_energy(const std::string& name) {
  add(name, "J", [](const Simulation& s) { return s.elastic_energy(); });
}

void ProbeRecorder::add_bed_height(const std::string& name, const Vec3& up, double top_fraction) {
  const Vec3 u = require_direction("probe '" + name + "' up", up);
  add(name, "m", [u, top_fraction](const Simulation& s) { return bed_height(s, u, top_fraction); });
}

void ProbeRecorder::record(const Simulation& simulation) {
  times_.push_back(simulation.time());
  for (std::size_t k = 0; k < series_.size(); ++k) series_[k].values.push_back(samplers_[k](simulation));
}

const TimeSeries& ProbeRecorder::get(const std::string& name) const {
  for (const TimeSeries& s : series_)
    if (s.name == name) return s;
  throw std::runtime_error("probe '" + name + "' does not exist; add it before recording");
}

void ProbeRecorder::write_csv(const std::string& path) const {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("probe CSV: cannot open '" + path + "' for writing; check the directory");
  out.precision(17);
  out << "time_s";
  for (const TimeSeries& s : series_) out << ',' << s.name << '_' << s.unit;
  out << '\n';
  for (std::size_t r = 0; r < times_.size(); ++r) {
    out << times_[r];
    for (const TimeSeries& s : series_) out << ',' << s.values[r];
    out << '\n';
  }
  if (!out) throw std::runtime_error("probe CSV: writing '" + path + "' failed; check disk space");
}

}  // namespace demfit::dem_core
