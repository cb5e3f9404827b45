#pragma once
// Whole case results cached on disk by their inputs (the resolved case JSON, parameters
// included): the s = 1 drum run that is Table 3's target and Fig. 4's reference is computed once.
// File: <cache_dir>/result_<16 hex>.json holding the key, the curves, tables and summary.
#include "demfit/cases/case_runner.hpp"

namespace demfit::cases {

// Returns the cached result of run_case(spec, {}, options) or computes and stores it.
// `computed` (optional) tells whether the case was run in this call.
CaseResult cached_case_result(const CaseSpec& spec, const CaseRunOptions& options, bool* computed = nullptr);

}  // namespace demfit::cases
