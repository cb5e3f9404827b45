// Writes an equivalent LIGGGHTS input into a temporary directory, runs it and times both codes.
#include "liggghts_compare.hpp"

#include <sys/resource.h>

#include <ctime>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "demfit/dem_core/simulation.hpp"

namespace demfit::bench {
namespace {
using namespace dem_core;

// Box [-0.03,0.03] x [-0.0125,0.0125] x [0,0.1] m; lattice points k*a inside the fill block.
constexpr double spacing = 2.05e-3, radius = 1.0e-3;  // 0.05 mm gaps: contacts within ~3 ms
constexpr double floor_z = 1.02e-3;  // floor plane 0.02 mm below the first lattice layer
constexpr double fill_lo[3] = {-0.0285, -0.011, 0.0011}, fill_hi[3] = {0.0285, 0.011, 0.0625};

std::string find_liggghts() {
  for (const char* name : {"liggghts", "lmp_serial", "lmp_auto"}) {
    const std::string cmd = std::string("command -v ") + name + " > /dev/null 2>&1";
    if (std::system(cmd.c_str()) == 0) return name;
  }
  return "";
}

Simulation make_box(double dt) {
  SimulationSettings s;
  s.law = ContactLawKind::hertz_mindlin;
  s.contact.restitution = 0.5;
  s.contact.frics = 0.3;
  s.time_step = dt;
  Simulation sim(s);
  sim.add_material({1.2e9 / (3.0 * (1.0 - 2.0 * 0.3)), 2500.0, 0.3});  // E = 1.2 GPa, nu = 0.3
  const WallContactParameters wall{0.3, 0.0, 0.0, 1.0};
  const double lo[3] = {-0.03, -0.0125, floor_z}, hi[3] = {0.03, 0.0125, 0.1};
  const Vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int a = 0; a < 3; ++a) {
    sim.add_wall({PlaneGeometry{lo[a] * axes[a], axes[a]}, FixedMotion{}, wall});
    sim.add_wall({PlaneGeometry{hi[a] * axes[a], -axes[a]}, FixedMotion{}, wall});
  }
  auto range = [](int a) { return std::pair<long, long>{std::lround(std::ceil(fill_lo[a] / spacing)),
                                                         std::lround(std::floor(fill_hi[a] / spacing))}; };
  const auto [i0, i1] = range(0);
  const auto [j0, j1] = range(1);
  const auto [k0, k1] = range(2);
  for (long k = k0; k <= k1; ++k)
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i) sim.add_particle({i * spacing, j * spacing, k * spacing}, radius);
  return sim;
}

void write_input(const std::filesystem::path& file, double dt, long steps) {
  std::ofstream in(file);
  in << "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n"
     << "communicate single vel yes\nunits si\n"
     << "region domain block -0.03 0.03 -0.0125 0.0125 0.0 0.1 units box\ncreate_box 1 domain\n"
     << "neighbor " << 0.3 * radius << " bin\nneigh_modify delay 0\n"
     << "hard_particles yes\n"
     << "fix m1 all property/global youngsModulus peratomtype 1.2e9\n"
     << "fix m2 all property/global poissonsRatio peratomtype 0.3\n"
     << "fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n"
     << "fix m4 all property/global coefficientFriction peratomtypepair 1 0.3\n"
     << "pair_style gran model hertz tangential history\npair_coeff * *\n"
     << "timestep " << dt << "\nfix gravi all gravity 9.81 vector 0.0 0.0 -1.0\n";
  const char* planes[3] = {"xplane", "yplane", "zplane"};
  const double lo[3] = {-0.03, -0.0125, floor_z}, hi[3] = {0.03, 0.0125, 0.1};
  for (int a = 0; a < 3; ++a)
    for (double v : {lo[a], hi[a]})
      in << "fix w" << a << (v == lo[a] ? "lo" : "hi") << " all wall/gran model hertz tangential history primitive type 1 "
         << planes[a] << ' ' << v << '\n';
  in << "lattice sc " << spacing << "\n"
     << "region fill block " << fill_lo[0] << ' ' << fill_hi[0] << ' ' << fill_lo[1] << ' ' << fill_hi[1] << ' '
     << fill_lo[2] << ' ' << fill_hi[2] << " units box\n"
     << "create_atoms 1 region fill\nset group all diameter " << 2 * radius << " density 2500\n"
     << "fix integr all nve/sphere\nthermo 1000\nrun " << steps << '\n';
}

}  // namespace

LiggghtsComparison compare_with_liggghts(long steps) {
  LiggghtsComparison c;
  c.steps = steps;
  Simulation sim = make_box(0.0);
  c.time_step = sim.time_step();
  c.particles = static_cast<long>(sim.particle_count());
  // CPU time of this process (1 thread) against LIGGGHTS' own loop time, which is CPU-bound too.
  const std::clock_t start = std::clock();
  sim.run_steps(static_cast<std::uint64_t>(steps));
  c.demfit_seconds = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  c.demfit_kinetic_energy = sim.kinetic_energy();
  const std::string exe = find_liggghts();
  if (exe.empty()) {
    c.note = "LIGGGHTS not found on PATH (liggghts / lmp_serial); install with: scripts/setup --bench "
             "(Debian package liggghts)";
    return c;
  }
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "demfit_bench_liggghts";
  std::filesystem::create_directories(dir);
  write_input(dir / "in.box", c.time_step, steps);
  const std::string cmd = "cd '" + dir.string() + "' && " + exe + " -in in.box -log log.liggghts > out.txt 2>&1";
  rusage before{}, after{};
  getrusage(RUSAGE_CHILDREN, &before);
  const int status = std::system(cmd.c_str());
  getrusage(RUSAGE_CHILDREN, &after);
  auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  c.liggghts_cpu_seconds = seconds(after.ru_utime) + seconds(after.ru_stime) - seconds(before.ru_utime) -
                           seconds(before.ru_stime);
  if (status != 0) {
    c.note = "LIGGGHTS run failed; see " + (dir / "out.txt").string();
    return c;
  }
  std::ifstream log(dir / "out.txt");
  std::stringstream text;
  text << log.rdbuf();
  const std::string s = text.str();
  std::smatch m;
  if (std::regex_search(s, m, std::regex("Created ([0-9]+) atoms"))) c.liggghts_particles = std::stol(m[1]);
  if (std::regex_search(s, m, std::regex("Loop time of ([0-9.eE+-]+)"))) c.liggghts_seconds = std::stod(m[1]);
  const std::regex thermo("\\n *" + std::to_string(steps) + " +[0-9]+ +([0-9.eE+-]+)");
  if (std::regex_search(s, m, thermo)) c.liggghts_kinetic_energy = std::stod(m[1]);
  c.ran = c.liggghts_seconds > 0.0;
  c.note = c.ran ? "ran " + exe + " in " + dir.string() : "could not parse the LIGGGHTS log " + (dir / "out.txt").string();
  return c;
}

}  // namespace demfit::bench
