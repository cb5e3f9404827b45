#pragma once
// Internal: the pellet-compression case kind (docs/spec.md 2.1): its case-file section and its run.
#include <nlohmann/json.hpp>

#include "demfit/cases/case_runner.hpp"

namespace demfit::cases::detail {

// The "pellet" section: strict reading (unknown keys and out-of-range values are errors naming
// the field) over `defaults`, and its JSON text (pellet_section.cpp).
PelletSpec parse_pellet_section(const nlohmann::json& section, PelletSpec defaults);
nlohmann::json pellet_section_json(const PelletSpec& pellet);

// Fill (cached), then the measured stage: piston loading (and unloading) (pellet_case.cpp).
CaseResult run_pellet_compression(const CaseSpec& fill_spec, const CaseSpec& spec, const CaseRunOptions& options);

}  // namespace demfit::cases::detail
