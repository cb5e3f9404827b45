// Snapshot writers: legacy VTK POLYDATA (ParaView-readable) and CSV.
#include "demfit/dem_core/snapshot.hpp"

#include <fstream>
#include <stdexcept>

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

void write_vectors(std::ofstream& out, const char* name, std::span<const Vec3> v) {
  out << "VECTORS " << name << " double\n";
  for (const Vec3& a : v) out << a.x << ' ' << a.y << ' ' << a.z << '\n';
}

}  // namespace

void write_vtk_snapshot(const Simulation& s, const std::string& path) {
  std::ofstream out = open_for_writing(path, "VTK snapshot");
  const std::size_t n = s.particle_count();
  out << "# vtk DataFile Version 3.0\n";
  out << "demfit particles t=" << s.time() << " s (SI units)\n";
  out << "ASCII\nDATASET POLYDATA\n";
  out << "POINTS " << n << " double\n";
  for (const Vec3& x : s.positions()) out << x.x << ' ' << x.y << ' ' << x.z << '\n';
  out << "VERTICES " << n << ' ' << 2 * n << '\n';
  for (std::size_t i = 0; i < n; ++i) out << "1 " << i << '\n';
  out << "POINT_DATA " << n << '\n';
  out << "SCALARS radius double 1\nLOOKUP_TABLE default\n";
  for (double r : s.radii()) out << r << '\n';
  write_vectors(out, "velocity", s.velocities());
  write_vectors(out, "angular_velocity", s.angular_velocities());
  if (!out) throw std::runtime_error("VTK snapshot: writing '" + path + "' failed; check disk space");
}

void write_csv_snapshot(const Simulation& s, const std::string& path) {
  std::ofstream out = open_for_writing(path, "CSV snapshot");
  out << "x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s,wx_rad_per_s,wy_rad_per_s,wz_rad_per_s\n";
  for (std::size_t i = 0; i < s.particle_count(); ++i) {
    const Vec3& x = s.positions()[i];
    const Vec3& v = s.velocities()[i];
    const Vec3& w = s.angular_velocities()[i];
    out << x.x << ',' << x.y << ',' << x.z << ',' << s.radii()[i] << ',' << v.x << ',' << v.y << ',' << v.z << ','
        << w.x << ',' << w.y << ',' << w.z << '\n';
  }
  if (!out) throw std::runtime_error("CSV snapshot: writing '" + path + "' failed; check disk space");
}

}  // namespace demfit::dem_core
