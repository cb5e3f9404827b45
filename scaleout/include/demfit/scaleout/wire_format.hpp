#pragma once
// What travels between ranks: jobs (experiment + parameter set) to workers, outcomes back to rank 0, as JSON text.
// nlohmann-json writes doubles in a shortest form that reads back to the same bits, so a run
// on a worker gives rank 0 exactly the curves a local run would (results identical to --jobs).
#include <string>

#include "demfit/identify/evaluator.hpp"

namespace demfit::scaleout {

std::string encode_parameters(const identify::ParameterSet& parameters);
identify::ParameterSet decode_parameters(const std::string& text);

// A job: the experiment index and its parameter set ({"experiment": e, "parameters": {...}}).
std::string encode_job(const identify::EvaluationJob& job);
identify::EvaluationJob decode_job(const std::string& text);

std::string encode_outcome(const identify::EvaluationOutcome& outcome);
identify::EvaluationOutcome decode_outcome(const std::string& text);

}  // namespace demfit::scaleout
