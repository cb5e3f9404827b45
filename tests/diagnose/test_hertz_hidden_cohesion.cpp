// A synthetic Hertz–Mindlin drum twin with a hidden SJKR cohesion: the GranuDrum case of
// cases/granudrum_mcc.json made small (SCG s = 4, 16,000 original particles = 250 simulated ones,
// 30 rpm, dt 6e-5 s = 0.3 Rayleigh times of the smallest particle, 1.5 s of rotation with the image
// surface averaged over the last 1.0 s in 41 snapshots; one evaluation ~1.3 s of one core). Measurements: its
// free_surface_image with cohesion on, plus 3 % Gaussian noise (cases::add_relative_noise, as `demfit simulate
// --noise`). Base variable: sliding friction; the candidates are the ones `demfit diagnose` gives this study
// (cases::diagnosis_model_and_candidates: cohesion, wall friction released from the tie,
// restitution released; rolling resistance is part of the base model at the case's 0.2). The
// workflow is not told which candidate is hidden, nor whether one is. The figures of these tests,
// and the simulate runs that chose the hidden level, are in
// docs/measurements/2026-12-06-hertz-twin-hidden-cohesion.md.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "dem_hidden_effects.hpp"
#include "demfit/cases/diagnosis_model.hpp"
#include "demfit/diagnose/least_squares.hpp"
#include "demfit/diagnose/model_scatter.hpp"
#include "demfit/diagnose/workflow.hpp"

using namespace demfit;
using namespace demfit::diagnose;
using namespace demfit::diagnose::hidden_effect_test;

namespace {

// Hidden SJKR cohesion energy density [J/m^3]. Measured with `demfit simulate` on the twin
// (image surface, RMS on the data abscissae): 1.5e4 moves the surface by 4.1 mm and steepens it
// from 52.3 to 56.4 degrees, against 1.4 mm between two runs 2e-7 apart in sliding friction (with
// and without cohesion) and 1.04 mm data noise; sliding friction at the top of its range (0.9)
// stays 2.4 mm away. Between 1.5e4 and 2e4 an s = 4 bed switches to rising as a block (456
// particles: 2e4 moves the surface by 22 mm).
constexpr double kHiddenCohesion = 1.5e4;

nlohmann::json twin_overrides() {
  return {{"time_step", {{"value", 6.0e-5}}},
          {"drum",
           {{"scale_factor", 4.0},
            {"particle_count", 16000},
            {"rpm", 30.0},
            {"duration", 1.5},
            {"surface_window", 1.0},
            {"surface_snapshots", 41}}}};
}

// Truth: sliding friction 0.5 (the case's value; the fit starts at 0.4), rolling friction 0.2 and
// restitution 0.3 as the case, walls tied to the particles' friction, cohesion `cohesion` (0: none).
Scenario twin_scenario(double cohesion, std::uint64_t seed) {
  Scenario s{"Hertz drum twin, hidden cohesion " + std::to_string(static_cast<int>(cohesion)) + " J/m3, seed " +
                 std::to_string(seed),
             "cases/granudrum_mcc.json",
             twin_overrides(),
             {{"frics", 0.1, 0.9, 0.4, false, 1.0}},
             {{"frics", 0.5}},
             {"free_surface_image"},
             seed,
             0.03};  // sigma 1.04 mm on a profile of +-35 mm
  if (cohesion > 0.0) s.truth["cohesion_energy_density"] = cohesion;
  s.noise_given = true;
  return s;
}

// The candidates `demfit diagnose` would give a study of this scenario.
std::vector<EffectCandidate> twin_candidates(const Scenario& s) {
  identify::StudySpec study;
  study.model_reference = s.case_name;
  study.model_overrides = s.overrides;
  study.variables = s.variables;
  study.base_dir = DEMFIT_SOURCE_DIR;
  std::vector<EffectCandidate> candidates;
  cases::diagnosis_model_and_candidates(study, candidates);
  return candidates;
}

// The machine's load while a seed ran (the wall times are shared-machine figures).
void print_load_average() {
  std::ifstream in("/proc/loadavg");
  std::string line;
  if (std::getline(in, line)) std::printf("  load average (1, 5, 15 min): %s\n", line.c_str());
}

// Seeds 41-45, or the range "first,last" in DEMFIT_HERTZ_TWIN_SEEDS (to spread the seeds over
// processes; each seed's diagnosis is independent of the others).
std::pair<std::uint64_t, std::uint64_t> twin_seeds() {
  std::uint64_t first = 41, last = 45;
  if (const char* text = std::getenv("DEMFIT_HERTZ_TWIN_SEEDS")) {
    unsigned long long a = 0, b = 0;
    if (std::sscanf(text, "%llu,%llu", &a, &b) == 2 && a <= b) first = a, last = b;
  }
  return {first, last};
}

bool names_cohesion_or_ties_it(const Diagnosis& d) {
  bool tied = false;
  for (int i : d.tied) tied = tied || d.refits[i].effect == "cohesion";
  const bool named = d.verdict == Verdict::effect_identified && d.refits[d.chosen].effect == "cohesion";
  return named || (d.verdict == Verdict::ambiguous && tied);
}

}  // namespace

// The target: the right name or "ambiguous" with cohesion among the tied, on every one of 5
// noise seeds, never another effect. 94-138 evaluations (~2-3 CPU-minutes) per seed; hidden ([.]),
// run it by name. Measured 2026-12-06 (docs/measurements/2026-12-06-hertz-twin-hidden-cohesion.md)
// this twin does NOT reach it: no seed names any effect, but seeds 41 and 43 end "unexplained"
// (cohesion best, its delta BIC above the threshold, k_c re-fitted to ~8.8e3 with the residual
// still structural) and 42, 44, 45 "no missing effect" (sliding friction 0.75-0.83 takes the
// cohesion's place within the scatter of the s = 4 bed). The test states the requirement and
// fails. With the data's own scatter counted (2026-12-07-hertz-twin-data-scatter.md): seed 41 names
// cohesion (k_c -8.5 %), 43 "unexplained", 42, 44, 45 "no missing effect"; 1 of 5, no wrong name.
TEST_CASE("A hidden SJKR cohesion in an s = 4 Hertz-Mindlin drum twin is named or called ambiguous on every seed",
          "[.][slow][drum]") {
  const auto [first, last] = twin_seeds();
  for (std::uint64_t seed = first; seed <= last; ++seed) {
    const Scenario s = twin_scenario(kHiddenCohesion, seed);
    const std::vector<EffectCandidate> candidates = twin_candidates(s);
    REQUIRE(std::any_of(candidates.begin(), candidates.end(), [](const auto& c) { return c.name == "cohesion"; }));
    const Outcome o = run(s, candidates);
    print_load_average();
    const Diagnosis& d = o.diagnosis;
    INFO("seed " << seed << ": " << d.summary);
    CHECK(d.base_analysis.structural);  // sliding friction alone leaves the cohesion in the residual
    CHECK(names_cohesion_or_ties_it(d));
    if (d.verdict == Verdict::effect_identified && d.refits[d.chosen].effect == "cohesion")
      CHECK(d.refits[d.chosen].fit.parameters.at("cohesion_energy_density") ==
            Approx(kHiddenCohesion).margin(0.3 * kHiddenCohesion));
  }
}

namespace {

// The named cohesion lies on the sliding friction-cohesion valley: within a factor of 3 of the
// hidden value, a cohesion and not a trace of one. Not 30 % as for one speed: on seed 44 the
// valley's floor runs from (frics 0.5, 15,000 J/m^3; replicated chi-square 110) to (0.64, 8,500;
// 127) within the replicas' chi-square spread (sd 18.9), so the data do not pin the value closer.
void check_named_cohesion_value(const Diagnosis& d) {
  if (d.verdict != Verdict::effect_identified || d.refits[d.chosen].effect != "cohesion") return;
  const double named = d.refits[d.chosen].fit.parameters.at("cohesion_energy_density");
  std::printf("  named cohesion %.0f J/m3 (%+.0f %% of the hidden value)\n", named,
              100.0 * (named / kHiddenCohesion - 1.0));
  CHECK(named > kHiddenCohesion / 3.0);
  CHECK(named < kHiddenCohesion * 3.0);
}

// The twin seen at two speeds, 15 and 45 rpm (the GranuDrum data's two), as two experiments of one
// study: cohesion and sliding friction change the surface differently with the speed, which one
// speed cannot show. The study's variables, candidates and noise (3 % of each surface's max|z|,
// estimated by diagnose, not given) are the one-speed twin's. The slow drum turns for 3 s, the
// same 0.75 turn the one-speed twin makes at 30 rpm in 1.5 s: in 1.5 s (0.375 turn) its s = 4 bed
// had not reached a steady avalanche regime and scattered 2.8-3.4 mm from run to run near the
// friction bound, three times the 45 rpm drum's.
identify::StudySpec two_speed_study(std::uint64_t seed) {
  identify::StudySpec study;
  study.name = "Hertz drum twin at 15 and 45 rpm, hidden cohesion, seed " + std::to_string(seed);
  study.base_dir = DEMFIT_SOURCE_DIR;
  for (const double rpm : {15.0, 45.0}) {
    nlohmann::json overrides = twin_overrides();
    overrides["drum"]["rpm"] = rpm;
    if (rpm == 15.0) overrides["drum"]["duration"] = 3.0;
    study.experiments.push_back({"rpm" + std::to_string(static_cast<int>(rpm)), "cases/granudrum_mcc.json",
                                 overrides, {}});
  }
  study.variables = {{"frics", 0.1, 0.9, 0.4, false, 1.0}};
  return study;
}

// Whether the verdict names an effect other than cohesion, or calls it ambiguous without cohesion
// among the tied.
bool names_another_effect(const Diagnosis& d) {
  if (d.verdict == Verdict::effect_identified) return d.refits[d.chosen].effect != "cohesion";
  return d.verdict == Verdict::ambiguous && !names_cohesion_or_ties_it(d);
}

// Delta BIC the hidden values themselves earn against the diagnosis's base, computed here from 4
// fresh runs at (frics 0.5, cohesion kHiddenCohesion), moved by round-off as the workflow's
// replicas are, under the diagnosis's whitened targets: the evidence the data hold for cohesion
// whatever a re-fit finds. A seed where it stays below the threshold cannot be asked to name it.
double delta_bic_at_hidden_values(const identify::Model& model, const Diagnosis& d,
                                  const std::vector<EffectCandidate>& candidates) {
  identify::ParameterSet truth = d.base.parameters;
  truth["frics"] = 0.5;
  truth["cohesion_energy_density"] = kHiddenCohesion;
  std::vector<FitVariable> variables = d.base_variables;
  for (const auto& c : candidates)
    if (c.name == "cohesion")
      for (const auto& p : c.parameters) variables.push_back({p.name, p.lower, p.upper, p.off_value});
  double chi_square = 0.0;
  int runs = 0;
  for (const Eigen::VectorXd& r : residuals_at(model, replica_parameter_sets(truth, variables, 4), d.targets, {}))
    if (r.size() > 0) chi_square += r.squaredNorm(), ++runs;
  REQUIRE(runs > 0);
  int points = 0;
  for (const auto& t : d.targets) points += static_cast<int>(t.data.x.size());
  const double gain = d.base_bic - bic(chi_square / runs, static_cast<int>(variables.size()), points);
  std::printf("  the hidden values (4 fresh runs): chi-square %.4g, delta BIC %.4g against a threshold of %.4g\n",
              chi_square / runs, gain, d.bic_threshold);
  return gain;
}

}  // namespace

// Measured 2026-12-06 with 1.5 s at 15 rpm (docs/measurements/2026-12-06-hertz-twin-hidden-cohesion.md:
// 2 of 5 seeds) and 2026-12-07 with 3 s (2026-12-07-hertz-twin-two-speed-same-turns.md: 3 of 5); with the
// data's own scatter counted (2026-12-07-hertz-twin-data-scatter.md): cohesion named on 4 of 5, no other
// name; seed 44's local re-fits miss a narrow optimum the criterion accepts at the hidden values
// (2026-12-07-hertz-twin-seed44-refit-starts.md). With the surrogate search
// (DEMFIT_DIAGNOSE_REFIT_SEARCH=30), which also judges the base at a searched optimum
// (2026-12-07-hertz-twin-base-search.md): cohesion named on seeds 41, 43 and 45; seeds 42 and 44
// "unexplained", where the hidden values themselves gain delta BIC 22.0 and 26.2 against thresholds
// of 37.8 and 40.8, so the test does not ask for the name there. Run it by name, seeds as the one-speed test
// (DEMFIT_HERTZ_TWIN_SEEDS), ~2x its cost per seed; DEMFIT_DIAGNOSE_REFIT_STARTS=3 as measured.
TEST_CASE("A hidden SJKR cohesion in an s = 4 Hertz-Mindlin drum twin seen at 15 and 45 rpm is named or called "
          "ambiguous wherever the hidden values pass the criterion, and no other effect is named",
          "[.][slow][drum]") {
  const auto [first, last] = twin_seeds();
  for (std::uint64_t seed = first; seed <= last; ++seed) {
    identify::StudySpec study = two_speed_study(seed);
    std::vector<EffectCandidate> candidates;
    const auto model = cases::diagnosis_model_and_candidates(study, candidates);
    REQUIRE(std::any_of(candidates.begin(), candidates.end(), [](const auto& c) { return c.name == "cohesion"; }));
    std::vector<double> sigma;
    add_synthetic_targets(study, *model, {{"frics", 0.5}, {"cohesion_energy_density", kHiddenCohesion}},
                          {"rpm15/free_surface_image", "rpm45/free_surface_image"}, 0.03, seed, sigma);
    const Outcome o = diagnose_and_report(study.name, study, *model, candidates, sigma, false);
    print_load_average();
    const Diagnosis& d = o.diagnosis;
    INFO("seed " << seed << ": " << d.summary);
    const double gain_at_truth = delta_bic_at_hidden_values(*model, d, candidates);
    if (gain_at_truth > d.bic_threshold) CHECK(names_cohesion_or_ties_it(d));
    CHECK_FALSE(names_another_effect(d));
    check_named_cohesion_value(d);
  }
}

// The control: the same twin without cohesion must not name cohesion (any other verdict is
// reported by the test's output, not judged here). Measured: "no missing effect", cohesion's
// re-fit delta BIC 16.6 against a threshold of 37.6; 181 evaluations.
TEST_CASE("Without cohesion the s = 4 Hertz-Mindlin drum twin does not name cohesion", "[.][slow][drum]") {
  const Scenario s = twin_scenario(0.0, 46);
  const Outcome o = run(s, twin_candidates(s));
  print_load_average();
  const Diagnosis& d = o.diagnosis;
  INFO(d.summary);
  CHECK_FALSE((d.verdict == Verdict::effect_identified && d.refits[d.chosen].effect == "cohesion"));
}

// The two-speed control: the same two-speed twin without cohesion must name nothing (any name is
// a wrong name here). Run it by name, seeds as above (default 41-45; ~20 min per seed on 2 cores
// with the search). Seed 46: with the local re-fits only, released wall friction is named (delta
// BIC 38.3 against 34.4; 2026-12-07-hertz-twin-refit-surrogate-search.md): the base fit's own run
// lay 36 below its replicas' mean chi-square. With DEMFIT_DIAGNOSE_REFIT_SEARCH=30, which searches
// the base variables too, the searched base (frics 0.501) fits as well as every candidate and
// nothing is named (2026-12-07-hertz-twin-base-search.md).
TEST_CASE("Without cohesion the s = 4 Hertz-Mindlin drum twin seen at 15 and 45 rpm names no effect",
          "[.][slow][drum]") {
  const auto [first, last] = twin_seeds();
  for (std::uint64_t seed = first; seed <= last; ++seed) {
    identify::StudySpec study = two_speed_study(seed);
    study.name = "Hertz drum twin at 15 and 45 rpm, no cohesion, seed " + std::to_string(seed);
    std::vector<EffectCandidate> candidates;
    const auto model = cases::diagnosis_model_and_candidates(study, candidates);
    std::vector<double> sigma;
    add_synthetic_targets(study, *model, {{"frics", 0.5}}, {"rpm15/free_surface_image", "rpm45/free_surface_image"},
                          0.03, seed, sigma);
    const Outcome o = diagnose_and_report(study.name, study, *model, candidates, sigma, false);
    print_load_average();
    INFO("seed " << seed << ": " << o.diagnosis.summary);
    CHECK(o.diagnosis.chosen < 0);
    CHECK(o.diagnosis.verdict != Verdict::ambiguous);
  }
}
