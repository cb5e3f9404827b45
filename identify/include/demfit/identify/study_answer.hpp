#pragma once
// The study's answer: the one rule every output asks (report.md, best_parameters.json, the
// warnings, `demfit export`, the reproduce tables), so no output can name another run.
//
// A finished study stored its answer (the run its final_selection chose, StudyLoop::finish):
// that run is the answer, whatever single run has the lowest objective. A study that has not
// finished (interrupted, or still running) has no answer yet; its lowest successful run is
// offered as "the lowest run so far", and says so.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/identify/study_store.hpp"

namespace demfit::identify {

struct StudyAnswer {
  const EvaluationRecord* run = nullptr;  ///< points into the runs passed in; null: no successful run
  bool finished = false;                  ///< the stored answer of a finished study
  std::string why;                        ///< one line: which rule chose this run
};

/// The answer among `runs` given the stored result (StudyStore::result()). Throws when a stored
/// answer names a run that is missing or failed (a damaged or edited store).
StudyAnswer study_answer(const std::vector<EvaluationRecord>& runs, const std::optional<nlohmann::json>& result,
                         const std::string& store_name);

}  // namespace demfit::identify
