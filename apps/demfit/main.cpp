// demfit: identify DEM contact parameters from measured curves.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>

#include "commands.hpp"
#include "demfit/dem_core/memory_retention.hpp"
#include "demfit/dem_core/openmp_waiting.hpp"

int main(int argc, char** argv) {
  // Idle OpenMP threads spin briefly, then sleep (dem_core/openmp_waiting.hpp: measured between
  // passive and active waiting). libgomp reads this before main, hence a re-execution; the user's
  // OMP_WAIT_POLICY or GOMP_SPINCOUNT wins.
  demfit::dem_core::use_bounded_spin_waiting(argv);
  // Freed memory stays in the process: a rebuild's fresh pages cost ~10 us each on a virtual
  // machine (dem_core/memory_retention.hpp).
  demfit::dem_core::retain_freed_memory();
  CLI::App app{
      "demfit — identify Discrete Element Method contact parameters (NORMK, SHEARK, damping, "
      "friction) from measured curves.\nAll quantities are SI unless a name states its unit "
      "(e.g. volume_cm3, pressure_MPa)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "demfit 0.1.0");
  demfit::apps::register_simulate(app);
  demfit::apps::register_identify(app);
  demfit::apps::register_reproduce(app);
  demfit::apps::register_diagnose(app);
  demfit::apps::register_target(app);
  demfit::apps::register_parameters(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) { return app.exit(e); } catch (const std::exception& e) {
    std::cerr << "demfit: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
