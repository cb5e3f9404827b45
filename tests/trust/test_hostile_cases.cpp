// The third battery of hostile inputs, case files: the Hertz–Mindlin cohesion and rolling fields,
// the drum's count limits, and runs whose budget or wall speed is absurd. Every case is refused
// before any simulation, with one line naming the field (rules: hostile_battery.hpp).
#include <catch2/catch.hpp>

#include <string>

#include "hostile_battery.hpp"

using namespace hostile;

namespace {

// The Hertz anchor drum (a Hertz–Mindlin case) with `edit` applied, as work/case.json.
std::function<void(const Sandbox&)> hertz_case(std::function<void(json&)> edit) {
  return [edit](const Sandbox& s) {
    json c = json::parse(trust::read_text(fs::path(DEMFIT_SOURCE_DIR) / "cases" / "hertz_anchor_drum.json"));
    edit(c);
    trust::write_text(s.work / "case.json", c.dump(2));
  };
}

// A shipped case file with `edit` applied, as work/case.json.
std::function<void(const Sandbox&)> shipped_case(std::string name, std::function<void(json&)> edit) {
  return [name, edit](const Sandbox& s) {
    json c = json::parse(trust::read_text(fs::path(DEMFIT_SOURCE_DIR) / "cases" / name));
    edit(c);
    trust::write_text(s.work / "case.json", c.dump(2));
  };
}

const std::vector<std::string> kSimulate = {"simulate", "case.json", "--out", "out"};

std::vector<std::string> simulate_with(std::string setting) {
  return {"simulate", "case.json", "--set", setting, "--out", "out"};
}

}  // namespace

TEST_CASE("Hertz-Mindlin cohesion and rolling fields outside their meaning are refused naming the field") {
  check_all({
      {"a negative cohesion energy density", hertz_case([](json& c) { c["contact"]["cohesion_energy_density"] = -1.0; }),
       kSimulate, "cohesion_energy_density"},
      {"a cohesion energy density given as text",
       hertz_case([](json& c) { c["contact"]["cohesion_energy_density"] = "strong"; }), kSimulate,
       "cohesion_energy_density"},
      {"a cohesion energy density of null", hertz_case([](json& c) { c["contact"]["cohesion_energy_density"] = nullptr; }),
       kSimulate, "cohesion_energy_density"},
      {"--set cohesion_energy_density=nan", hertz_case([](json&) {}), simulate_with("cohesion_energy_density=nan"),
       "cohesion_energy_density"},
      {"--set cohesion_energy_density=-5", hertz_case([](json&) {}), simulate_with("cohesion_energy_density=-5"),
       "cohesion_energy_density"},
      {"a cohesion so large that the contact law no longer holds",
       hertz_case([](json& c) { c["contact"]["cohesion_energy_density"] = 1e9; }), kSimulate,
       "cohesion_energy_density"},
      {"an unknown cohesion model", hertz_case([](json& c) { c["contact"]["cohesion_model"] = "jkr"; }), kSimulate,
       "cohesion_model"},
      {"an unknown rolling model", hertz_case([](json& c) { c["contact"]["rolling_model"] = "epsd3"; }), kSimulate,
       "rolling_model"},
      {"epsd2 rolling with the LS-DYNA law",
       shipped_case("rotary_drum.json", [](json& c) { c["contact"]["rolling_model"] = "epsd2"; }), kSimulate,
       "rolling_model"},
      {"SJKR cohesion with the LS-DYNA law",
       shipped_case("rotary_drum.json", [](json& c) { c["contact"]["cohesion_energy_density"] = 1000.0; }),
       kSimulate, "cohesion_energy_density"},
      {"a cohesion model with the LS-DYNA law",
       shipped_case("pellet_compression.json", [](json& c) { c["contact"]["cohesion_model"] = "sjkr2"; }), kSimulate,
       "cohesion_model"},
      {"a wall friction ratio without the tie to the particles' friction",
       hertz_case([](json& c) {
         c["wall_contact"]["friction_as_particles"] = false;
         c["wall_contact"]["frics"] = 0.3;
         c["wall_contact"]["friction_ratio"] = 0.5;
       }),
       kSimulate, "friction_ratio"},
      {"a negative wall friction ratio", hertz_case([](json& c) { c["wall_contact"]["friction_ratio"] = -0.5; }),
       kSimulate, "friction_ratio"},
      {"--set rolling_model=epsd2 on the LS-DYNA drum", shipped_case("rotary_drum.json", [](json&) {}),
       simulate_with("contact.rolling_model=epsd2"), "rolling_model"},
      {"--set cohesion_model=sjkr3 on the Hertz drum", hertz_case([](json&) {}),
       simulate_with("contact.cohesion_model=sjkr3"), "cohesion_model"},
      {"a restitution of 0", hertz_case([](json& c) { c["contact"]["restitution"] = 0.0; }), kSimulate, "restitution"},
      {"a restitution of 1.5", hertz_case([](json& c) { c["contact"]["restitution"] = 1.5; }), kSimulate,
       "restitution"},
  });
}

TEST_CASE("drum count fields above their documented limits are refused naming the field") {
  check_all({
      {"surface_snapshots 1e6", hertz_case([](json& c) { c["drum"]["surface_snapshots"] = 1000000; }), kSimulate,
       "drum.surface_snapshots"},
      {"surface_points 1e7", hertz_case([](json& c) { c["drum"]["surface_points"] = 10000000; }), kSimulate,
       "drum.surface_points"},
      {"image pixels 1e5", hertz_case([](json& c) { c["drum"]["image"]["pixels"] = 100000; }), kSimulate,
       "drum.image.pixels"},
      {"image points 1e7", hertz_case([](json& c) { c["drum"]["image"]["points"] = 10000000; }), kSimulate,
       "drum.image.points"},
      {"a torque interval longer than the run", hertz_case([](json& c) { c["drum"]["torque_interval"] = 5.0; }),
       kSimulate, "drum.torque_interval"},
      {"a torque interval of 1e300 s", hertz_case([](json& c) { c["drum"]["torque_interval"] = 1e300; }), kSimulate,
       "drum.torque_interval"},
  });
}

TEST_CASE("runs estimated at days, or whose walls jump over contacts, are refused before any work") {
  check_all({
      {"a Hertz drum turning for 1e6 s", hertz_case([](json& c) { c["drum"]["duration"] = 1e6; }), kSimulate,
       "DEMFIT_ALLOW_LONG_RUNS=1"},
      {"a paper drum turning for 1e5 s", shipped_case("rotary_drum.json", [](json& c) { c["drum"]["duration"] = 1e5; }),
       kSimulate, "DEMFIT_ALLOW_LONG_RUNS=1"},
      {"a Hertz drum at a time step of 1e-12 s", hertz_case([](json& c) { c["time_step"] = {{"value", 1e-12}}; }),
       kSimulate, "DEMFIT_ALLOW_LONG_RUNS=1"},
      {"a pellet bed with Young's modulus 1e300 Pa",
       shipped_case("pellet_compression.json", [](json& c) { c["particle"]["youngs_modulus"] = 1e300; }), kSimulate,
       "DEMFIT_ALLOW_LONG_RUNS=1"},
      {"a pellet bed of density 1e-300 kg/m3",
       shipped_case("pellet_compression.json", [](json& c) { c["particle"]["density"] = 1e-300; }), kSimulate,
       "DEMFIT_ALLOW_LONG_RUNS=1"},
      {"a pellet piston crawling at 1e-9 m/s",
       shipped_case("pellet_compression.json", [](json& c) { c["pellet"]["piston_speed"] = 1e-9; }), kSimulate,
       "DEMFIT_ALLOW_LONG_RUNS=1"},
      {"a Hertz drum at 1e6 rpm", hertz_case([](json& c) { c["drum"]["rpm"] = 1e6; }), kSimulate,
       "'drum.rpm': the wall moves"},
      {"a Hertz drum at -1e6 rpm", hertz_case([](json& c) { c["drum"]["rpm"] = -1e6; }), kSimulate,
       "'drum.rpm': the wall moves"},
      {"a paper drum at 1e5 rpm by --set", shipped_case("rotary_drum.json", [](json&) {}),
       simulate_with("drum.rpm=100000"), "'drum.rpm': the wall moves"},
      {"a pellet piston at 1e4 m/s",
       shipped_case("pellet_compression.json", [](json& c) { c["pellet"]["piston_speed"] = 1e4; }), kSimulate,
       "'pellet.piston_speed': the wall moves"},
  });
}
