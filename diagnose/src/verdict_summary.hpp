#pragma once
// The one-paragraph verdict of a diagnosis with its numbers (Diagnosis::summary). Internal to
// the diagnose library.
#include <string>

#include "demfit/diagnose/workflow.hpp"

namespace demfit::diagnose::detail {

// "runs p = ..., lag-1 autocorrelation ..., variance ratio ..., smooth structure p = ..."
std::string tests_text(const ResidualAnalysis& analysis);

// The verdict in words: what was found, the residual tests before and after, the numbers; when no
// effect is named, also the candidates these data cannot detect (ScreeningScore::full_range_gain).
std::string summarise(const Diagnosis& diagnosis);

}  // namespace demfit::diagnose::detail
