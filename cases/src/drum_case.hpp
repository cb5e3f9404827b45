#pragma once
// Internal: the rotary-drum adapter (SPEC 2.2).
#include "demfit/cases/case_runner.hpp"

namespace demfit::cases::detail {

CaseResult run_rotary_drum(const CaseSpec& fill_spec, const CaseSpec& spec, const CaseRunOptions& options);

}  // namespace demfit::cases::detail
