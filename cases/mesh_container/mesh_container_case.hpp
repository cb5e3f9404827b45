#pragma once
// Internal: the mesh_container case kind (docs/mesh-container.md): particles poured into the
// user's STL geometry (fixed and moving parts), settled under gravity (-z), and the curves a user
// measures there: heap_angle, discharge_mass, moving_part_torque.
#include <array>
#include <filesystem>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/cases/case_runner.hpp"

namespace demfit::cases::detail {

// The "mesh_container" section of `document` into spec.mesh_container (strict; errors name the
// field and the fix); reads every STL file now, relative to `base_dir` (mesh_container_section.cpp).
void parse_mesh_container_section(const nlohmann::json& document, CaseSpec& spec,
                                  const std::filesystem::path& base_dir);
nlohmann::json mesh_container_section_json(const MeshContainerSpec& section);

// Length of one STL unit [m] ("m", "cm", "mm", "um", "in"); 0 for an unknown unit.
double metres_per_stl_unit(std::string_view unit);

// Pour, settle and measure in one run (mesh_container_case.cpp).
CaseResult run_mesh_container(const CaseSpec& spec, const CaseRunOptions& options);

// The name printed beside every heap angle: which definition it is.
inline constexpr std::string_view kHeapAngleDefinition =
    "pedestal line fit: max(z + R) per annulus of the radial window, least-squares slope s, angle = atan(-s)";

// Heap angle of repose [deg] by kHeapAngleDefinition (heap_angle.cpp): the window [r_min, r_max]
// around the heap axis (center x, y) is cut into `bins` equal annuli; in each, the surface height
// is the largest z + R of the particles (those with z >= base_z); a least-squares line
// h = a + s r through (annulus mid-radius, height) gives the angle atan(-s). NaN when fewer than
// two annuli hold a particle.
double heap_angle_degrees(const std::vector<std::array<double, 3>>& positions, const std::vector<double>& radii,
                          const HeapAngleSpec& heap);

}  // namespace demfit::cases::detail
