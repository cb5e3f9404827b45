#pragma once
// Particle snapshots for inspection: legacy VTK (ASCII POLYDATA, one vertex per particle, point
// data "radius" [m], "velocity" [m/s], "angular_velocity" [rad/s]; ParaView: Glyph filter, scale
// by radius) and CSV (header with units). Throw std::runtime_error if the file cannot be written.
#include <string>

namespace demfit::dem_core {

class Simulation;

void write_vtk_snapshot(const Simulation& simulation, const std::string& path);
/// Columns: x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s,wx_rad_per_s,wy_rad_per_s,wz_rad_per_s
void write_csv_snapshot(const Simulation& simulation, const std::string& path);

}  // namespace demfit::dem_core
