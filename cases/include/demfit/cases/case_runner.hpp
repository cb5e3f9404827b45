#pragma once
// Runs a case (pellet compression or rotary drum) and returns its curves, tables and a summary.
// This is the one entry point the CLI and the Model adapters use.
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/curve_table.hpp"
#include "demfit/cases/progress.hpp"
#include "demfit/identify/model.hpp"

namespace demfit::cases {

struct CaseRunOptions {
  int threads = 1;                     // OpenMP threads of the simulation
  ProgressCallback progress;           // may be empty
  std::filesystem::path snapshot_dir;  // VTK snapshots at spec.output.snapshot_times; empty = none
  std::filesystem::path cache_dir;     // settled fills; empty = default_cache_dir()
};

// A drum summary's overlap line (dem_core/overlap_statistics.hpp): its label, and a value "mean / max"
// in % of the smaller radius. Spelt once: `reproduce table3` reads the line back.
inline constexpr std::string_view kParticleOverlapLabel =
    "particle overlap at the end, mean / max [% of the smaller radius]";

struct CaseResult {
  identify::CurveSet curves;                                 // named curves (the Model's output)
  std::map<std::string, CurveTable> tables;                  // file stem -> multi-column table (histories)
  std::vector<std::pair<std::string, std::string>> summary;  // (label with unit, value) lines
};

// The fill (pellet pouring + settling, drum packing + densification) uses the spec's own contact
// values, so it is shared by every evaluation and cached; `parameters` (identified-parameter
// names, see parameter_names()) override the contact values for the measured stage only
// (compression, rotation). Throws std::runtime_error on bad input or a failed simulation.
CaseResult run_case(const CaseSpec& spec, const identify::ParameterSet& parameters, const CaseRunOptions& options);

// $DEMFIT_CACHE_DIR, else $XDG_CACHE_HOME/demfit, else $HOME/.cache/demfit, else ./.demfit-cache.
std::filesystem::path default_cache_dir();

}  // namespace demfit::cases
