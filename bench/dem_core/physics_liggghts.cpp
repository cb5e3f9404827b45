// LIGGGHTS input and output of the physics cross-check (physics_liggghts.hpp).
#include "physics_liggghts.hpp"

#include <fstream>
#include <regex>
#include <sstream>

#include "child_process.hpp"

namespace demfit::bench {
namespace {

std::string rolling_word(dem_core::RollingModel model) {
  switch (model) {
    case dem_core::RollingModel::constant_torque:
      return "cdt";
    case dem_core::RollingModel::elastic_plastic:
      return "epsd2";
  }
  return "";
}

std::string cohesion_word(dem_core::CohesionModel model) {
  switch (model) {
    case dem_core::CohesionModel::sjkr:
      return "sjkr";
    case dem_core::CohesionModel::sjkr2:
      return "sjkr2";
  }
  return "";
}

/// Thermo lines "step atoms ke torque centre_x" after step 0: one per window.
std::vector<WindowFigures> parse_windows(const std::string& log, double time_step) {
  std::vector<WindowFigures> windows;
  const std::string number = "([-+0-9.eE]+)";
  const std::regex line("^ *([0-9]+) +[0-9]+ +" + number + " +" + number + " +" + number + " *$");
  std::istringstream in(log);
  for (std::string text; std::getline(in, text);) {
    std::smatch m;
    if (!std::regex_match(text, m, line)) continue;
    const long step = std::stol(m[1]);
    if (step == 0) continue;  // fix ave/time has no window yet
    windows.push_back({static_cast<double>(step) * time_step, std::stod(m[3]), std::stod(m[4])});
  }
  return windows;
}

/// `dump custom ... id x y z radius` snapshots after step 0.
std::vector<BedSnapshot> parse_dump(std::istream& in, double time_step) {
  std::vector<BedSnapshot> snapshots;
  std::string text;
  while (std::getline(in, text)) {
    if (text.rfind("ITEM: TIMESTEP", 0) != 0) continue;
    long step = 0;
    std::size_t atoms = 0;
    in >> step;
    std::getline(in, text);  // rest of the step line
    std::getline(in, text);  // ITEM: NUMBER OF ATOMS
    in >> atoms;
    std::getline(in, text);
    for (int k = 0; k < 5; ++k) std::getline(in, text);  // box bounds (4 lines) and ITEM: ATOMS header
    BedSnapshot s;
    s.time = static_cast<double>(step) * time_step;
    s.positions.resize(atoms);
    s.radii.resize(atoms);
    for (std::size_t i = 0; i < atoms; ++i) {
      long id = 0;
      in >> id >> s.positions[i][0] >> s.positions[i][1] >> s.positions[i][2] >> s.radii[i];
    }
    if (!in) break;
    if (step > 0) snapshots.push_back(std::move(s));
  }
  return snapshots;
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::string liggghts_model_words(const LawVariant& v) {
  std::string words = "hertz tangential history";
  if (v.cohesion_energy_density > 0.0) words += " cohesion " + cohesion_word(v.cohesion);
  return words + " rolling_friction " + rolling_word(v.rolling);
}

void write_physics_input(const std::filesystem::path& dir, const HertzDrumSpec& spec, const LawVariant& v, long steps,
                         long window_steps) {
  std::ofstream in(dir / ("in." + v.name));
  in.precision(17);
  const std::string model = liggghts_model_words(v);
  in << "# Physics cross-check, variant " << v.name << ": demfit's bed (bed.data) continued in the rotating\n"
     << "# STL drum (drum.stl) with `" << model << "`. SI units.\n"
     << "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n"
     << "communicate single vel yes\nunits si\nprocessors 1 1 1\nread_data bed.data\n"
     << "neighbor " << spec.skin << " bin\nneigh_modify delay 0\n"
     << "fix m1 all property/global youngsModulus peratomtype " << spec.youngs_modulus << '\n'
     << "fix m2 all property/global poissonsRatio peratomtype " << spec.poisson_ratio << '\n'
     << "fix m3 all property/global coefficientRestitution peratomtypepair 1 " << spec.restitution << '\n'
     << "fix m4 all property/global coefficientFriction peratomtypepair 1 " << spec.sliding_friction << '\n'
     << "fix m5 all property/global coefficientRollingFriction peratomtypepair 1 " << spec.rolling_friction << '\n';
  if (v.cohesion_energy_density > 0.0)
    in << "fix m6 all property/global cohesionEnergyDensity peratomtypepair 1 " << v.cohesion_energy_density << '\n';
  in << "pair_style gran model " << model << "\npair_coeff * *\n"
     << "timestep " << spec.time_step << '\n'
     << "fix gravi all gravity " << spec.gravity
     << " vector 0.0 -1.0 0.0\n"
     // The mesh (atom type 1) gets the particles' material and the same cohesion as the pairs.
     << "fix cad all mesh/surface/stress file drum.stl type 1 reference_point 0. 0. 0.\n"
     << "fix walls all wall/gran model " << model << " mesh n_meshes 1 meshes cad\n"
     << "fix spin all move/mesh mesh cad rotate origin 0. 0. 0. axis 0. 0. 1. period "
     << 1.0 / spec.revolutions_per_second << '\n'
     << "fix integr all nve/sphere\ncompute centre all com\n"
     // Drive torque: minus the moment the particles exert on the drum about +z.
     << "variable drive equal -f_cad[6]\nvariable centre_x equal c_centre[1]\n"
     << "fix windows all ave/time 10 " << window_steps / 10 << ' ' << window_steps << " v_drive v_centre_x\n"
     << "thermo_style custom step atoms ke f_windows[1] f_windows[2]\nthermo " << window_steps << '\n'
     << "thermo_modify norm no lost ignore\n"
     << "dump snapshots all custom " << window_steps << " snapshots." << v.name << " id x y z radius\n"
     << "run " << steps << '\n';
}

PhysicsRun run_liggghts_physics(const std::filesystem::path& dir, const LawVariant& v, double time_step) {
  PhysicsRun run;
  const std::filesystem::path out = dir / ("physics." + v.name + ".out");
  const ChildResult child = run_child({"liggghts", "-echo", "none", "-in", "in." + v.name, "-log", "none"}, dir, out);
  run.wall_seconds = child.wall_seconds;
  if (!child.started || child.exit_code != 0) {
    run.note = "LIGGGHTS failed (exit " + std::to_string(child.exit_code) + "); see " + out.string();
    return run;
  }
  run.windows = parse_windows(read_text(out), time_step);
  std::ifstream dump(dir / ("snapshots." + v.name));
  run.snapshots = parse_dump(dump, time_step);
  run.ok = !run.windows.empty() && !run.snapshots.empty();
  if (!run.ok) run.note = "could not read the windows or snapshots of " + out.string();
  return run;
}

}  // namespace demfit::bench
