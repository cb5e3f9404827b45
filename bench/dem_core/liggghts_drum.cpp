// LIGGGHTS input for the Hertz benchmark drum, written from demfit's state, and its run.
#include "liggghts_drum.hpp"

#include <unistd.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <variant>

#include "child_process.hpp"
#include "drum_mesh.hpp"

namespace demfit::bench {
namespace {
using namespace dem_core;

void write_data_file(const std::filesystem::path& file, const HertzDrumSpec& spec, const Simulation& sim) {
  std::ofstream out(file);
  out.precision(17);
  const double half = spec.drum_radius + 5.0 * spec.radius;
  out << "LIGGGHTS data file (SI units) written by demfit bench_dem: drum bed at t = " << sim.time() << " s\n\n"
      << sim.particle_count() << " atoms\n1 atom types\n\n"
      << -half << ' ' << half << " xlo xhi\n"
      << -half << ' ' << half << " ylo yhi\n"
      << -5.0 * spec.radius << ' ' << spec.depth + 5.0 * spec.radius << " zlo zhi\n\nAtoms\n\n";
  // atom_style granular: atom-ID atom-type diameter density x y z
  for (std::size_t i = 0; i < sim.particle_count(); ++i) {
    const Vec3& x = sim.positions()[i];
    out << i + 1 << " 1 " << 2.0 * sim.radii()[i] << ' ' << spec.density << ' ' << x.x << ' ' << x.y << ' ' << x.z
        << '\n';
  }
  out << "\nVelocities\n\n";  // atom-ID vx vy vz wx wy wz
  for (std::size_t i = 0; i < sim.particle_count(); ++i) {
    const Vec3& v = sim.velocities()[i];
    const Vec3& w = sim.angular_velocities()[i];
    out << i + 1 << ' ' << v.x << ' ' << v.y << ' ' << v.z << ' ' << w.x << ' ' << w.y << ' ' << w.z << '\n';
  }
}

void write_input(const std::filesystem::path& file, const HertzDrumSpec& spec, long steps) {
  std::ofstream in(file);
  in.precision(17);
  in << "# Hertz benchmark drum: same bed, contact law and step as demfit's (bench/dem_core/hertz_drum.hpp)\n"
     << "variable px index 1\nvariable py index 1\nvariable pz index 1\n"
     << "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n"
     << "communicate single vel yes\nunits si\nprocessors ${px} ${py} ${pz}\nread_data bed.data\n"
     << "neighbor " << spec.skin << " bin\nneigh_modify delay 0\n"
     << "fix m1 all property/global youngsModulus peratomtype " << spec.youngs_modulus << '\n'
     << "fix m2 all property/global poissonsRatio peratomtype " << spec.poisson_ratio << '\n'
     << "fix m3 all property/global coefficientRestitution peratomtypepair 1 " << spec.restitution << '\n'
     << "fix m4 all property/global coefficientFriction peratomtypepair 1 " << spec.sliding_friction << '\n'
     << "fix m5 all property/global coefficientRollingFriction peratomtypepair 1 " << spec.rolling_friction << '\n'
     << "pair_style gran model hertz tangential history rolling_friction cdt\npair_coeff * *\n"
     << "timestep " << spec.time_step << '\n'
     << "fix gravi all gravity " << spec.gravity << " vector 0.0 -1.0 0.0\n"
     << "fix cad all mesh/surface file drum.stl type 1\n"
     << "fix walls all wall/gran model hertz tangential history rolling_friction cdt mesh n_meshes 1 meshes cad\n"
     << "fix spin all move/mesh mesh cad rotate origin 0. 0. 0. axis 0. 0. 1. period "
     << 1.0 / spec.revolutions_per_second << '\n'
     << "fix integr all nve/sphere\ncompute centre all com\n"
     << "thermo_style custom step atoms ke c_centre[1] c_centre[2]\nthermo " << steps << '\n'
     << "thermo_modify norm no lost ignore\nrun " << steps << '\n';
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void parse_log(const std::string& s, LiggghtsRun& run) {
  std::smatch m;
  const std::string number = "([-0-9.eE+]+)";
  if (std::regex_search(
          s, m, std::regex("Loop time of " + number + " on ([0-9]+) procs for ([0-9]+) steps with ([0-9]+) atoms"))) {
    run.loop_seconds = std::stod(m[1]);
    run.procs = std::stol(m[2]);
    run.steps = std::stol(m[3]);
    run.atoms = std::stol(m[4]);
  }
  if (std::regex_search(s, m, std::regex("Neighbor list builds = ([0-9]+)"))) run.neighbour_builds = std::stol(m[1]);
  if (std::regex_search(s, m, std::regex("Pair +time \\(%\\) = " + number))) run.pair_seconds = std::stod(m[1]);
  if (std::regex_search(s, m, std::regex("Neigh +time \\(%\\) = " + number))) run.neighbour_seconds = std::stod(m[1]);
  if (std::regex_search(s, m, std::regex("Comm +time \\(%\\) = " + number))) run.comm_seconds = std::stod(m[1]);
  const std::regex last("\\n *" + std::to_string(run.steps) + " +[0-9]+ +" + number + " +" + number + " +" + number);
  if (run.steps > 0 && std::regex_search(s, m, last)) {
    run.kinetic_energy = std::stod(m[1]);
    run.centre_x = std::stod(m[2]);
    run.centre_y = std::stod(m[3]);
  }
  run.ok = run.loop_seconds > 0.0;
}

}  // namespace

std::string liggghts_executable() { return find_on_path("liggghts").empty() ? "" : "liggghts"; }

std::size_t write_liggghts_drum(const std::filesystem::path& dir, const HertzDrumSpec& spec, const Simulation& sim,
                                long steps, const DrumMeshShape& shape) {
  std::filesystem::create_directories(dir);
  write_data_file(dir / "bed.data", spec, sim);
  write_input(dir / "in.drum", spec, steps);
  std::ofstream stl(dir / "drum.stl");
  DrumMeshRequest request{spec.drum_radius, spec.depth,        sim.wall(0).rotation_angle,
                          shape.segments,   shape.shell_rings, shape.cap_rings};
  return write_drum_stl(stl, request);
}

LiggghtsRun run_liggghts_drum(const std::filesystem::path& dir, int px, int py, int pz, const std::string& out_name) {
  std::vector<std::string> argv;
  const int ranks = px * py * pz;
  if (ranks > 1) {
    argv = {"mpirun"};
    if (geteuid() == 0) argv.push_back("--allow-run-as-root");
    // Unbound, like demfit's OpenMP threads, so both share the cores the same way; idle ranks
    // yield the core, as demfit's threads give it away after a short spin (busy-polling ranks
    // took 7x longer than 1 rank at load 6 on 2 cores, measured).
    for (const char* a : {"--bind-to", "none", "--mca", "mpi_yield_when_idle", "1", "-np"}) argv.push_back(a);
    argv.push_back(std::to_string(ranks));
  }
  for (const std::string& a : {std::string("liggghts"), std::string("-echo"), std::string("none"), std::string("-in"),
                               std::string("in.drum"), std::string("-log"), out_name + ".log"})
    argv.push_back(a);
  for (const auto& [name, value] : {std::pair{"px", px}, std::pair{"py", py}, std::pair{"pz", pz}}) {
    argv.push_back("-var");
    argv.push_back(name);
    argv.push_back(std::to_string(value));
  }
  LiggghtsRun run;
  const ChildResult child = run_child(argv, dir, dir / (out_name + ".out"));
  if (!child.started || child.exit_code != 0) {
    run.note =
        "LIGGGHTS failed (exit " + std::to_string(child.exit_code) + "); see " + (dir / (out_name + ".out")).string();
    return run;
  }
  parse_log(read_text(dir / (out_name + ".out")), run);
  if (!run.ok) run.note = "could not parse the LIGGGHTS output " + (dir / (out_name + ".out")).string();
  return run;
}

}  // namespace demfit::bench
