#pragma once
// Internal: the pellet-compression adapter (SPEC 2.1).
#include "demfit/cases/case_runner.hpp"

namespace demfit::cases::detail {

CaseResult run_pellet_compression(const CaseSpec& fill_spec, const CaseSpec& spec, const CaseRunOptions& options);

}  // namespace demfit::cases::detail
