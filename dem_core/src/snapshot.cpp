// Snapshot writers: legacy VTK POLYDATA (ParaView-readable) and CSV.
#include "demfit/dem_core/snapshot.hpp"

#include <fstream>
#include <stdexcept>
#include <vector>

#include "demfit/dem_core/simulation.hpp"

namespace demfit::dem_core {
namespace {

std::ofstream open_for_writing(const std::string& path, const char* what) {
  std::ofstream out(path);
  if (!out)
    throw std::runtime_error(std::string(what) + ": cannot open '" + path + "' for writing; check the directory");
  out.precision(9);
  return out;
}

void write_rows(std::ofstream& out, std::span<const Vec3> v, const std::vector<std::size_t>& order) {
  for (std::size_t i : order) out << v[i].x << ' ' << v[i].y << ' ' << v[i].z << '\n';
}

void write_vectors(std::ofstream& out, const char* name, std::span<const Vec3> v,
                   const std::vector<std::size_t>& order) {
  out << "VECTORS " << name << " double\n";
  write_rows(out, v, order);
}

}  // namespace

void write_vtk_snapshot(const Simulation& s, const std::string& path) {
  std::ofstream out = open_for_writing(path, "VTK snapshot");
  const std::size_t n = s.particle_count();
  const std::vector<std::size_t> order = s.particles().indices_by_id();  // files never show memory order
  out << "# vtk DataFile Version 3.0\n";
  out << "demfit particles t=" << s.time() << " s (SI units)\n";
  out << "ASCII\nDATASET POLYDATA\n";
  out << "POINTS " << n << " double\n";
  write_rows(out, s.positions(), order);
  out << "VERTICES " << n << ' ' << 2 * n << '\n';
  for (std::size_t i = 0; i < n; ++i) out << "1 " << i << '\n';
  out << "POINT_DATA " << n << '\n';
  out << "SCALARS radius double 1\nLOOKUP_TABLE default\n";
  for (std::size_t i : order) out << s.radii()[i] << '\n';
  out << "SCALARS id int 1\nLOOKUP_TABLE default\n";
  for (std::size_t i : order) out << s.particles().id[i] << '\n';
  write_vectors(out, "velocity", s.velocities(), order);
  write_vectors(out, "angular_velocity", s.angular_velocities(), order);
  if (!out) throw std::runtime_error("VTK snapshot: writing '" + path + "' failed; check disk space");
}

void write_csv_snapshot(const Simulation& s, const std::string& path) {
  std::ofstream out = open_for_writing(path, "CSV snapshot");
  out << "x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s,wx_rad_per_s,wy_rad_per_s,wz_rad_per_s\n";
  for (std::size_t i : s.particles().indices_by_id()) {
    const Vec3& x = s.positions()[i];
    const Vec3& v = s.velocities()[i];
    const Vec3& w = s.angular_velocities()[i];
    out << x.x << ',' << x.y << ',' << x.z << ',' << s.radii()[i] << ',' << v.x << ',' << v.y << ',' << v.z << ','
        << w.x << ',' << w.y << ',' << w.z << '\n';
  }
  if (!out) throw std::runtime_error("CSV snapshot: writing '" + path + "' failed; check disk space");
}

}  // namespace demfit::dem_core
