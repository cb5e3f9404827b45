#pragma once
// Internal: the rotary-drum case kind (docs/spec.md 2.2 and the general drum): its case-file
// section and its run.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "demfit/cases/case_runner.hpp"

namespace demfit::cases::detail {

// The "drum" section of `document` into spec.drum (strict; errors name the field), and the
// particle fields a size distribution replaces (drum_section.cpp).
void parse_drum_section(const nlohmann::json& document, CaseSpec& spec, const std::filesystem::path& base_dir);
nlohmann::json drum_section_json(const DrumSpec& drum);

// The four ways to give the fill amount, exactly one per case file (FillBy; drum_section.cpp).
inline constexpr const char* kDrumFillKeys[] = {"fill_fraction", "fill_volume_ml", "particle_count", "fill_mass"};

// Fill (cached, drum_powder.cpp), then the measured stage: rotation (drum_case.cpp).
CaseResult run_rotary_drum(const CaseSpec& fill_spec, const CaseSpec& spec, const CaseRunOptions& options);

}  // namespace demfit::cases::detail
