// The study's answer (see study_answer.hpp).
#include "demfit/identify/study_answer.hpp"

#include <stdexcept>

namespace demfit::identify {

StudyAnswer study_answer(const std::vector<EvaluationRecord>& runs, const std::optional<nlohmann::json>& result,
                         const std::string& store_name) {
  StudyAnswer answer;
  if (result && result->contains("best_iteration") && result->contains("best_point")) {
    const nlohmann::json& iteration = result->at("best_iteration");
    const nlohmann::json& point = result->at("best_point");
    if (!iteration.is_number_integer() || !point.is_number_integer())
      throw std::runtime_error("study store '" + store_name +
                               "': the stored answer has no valid run number; rerun the study into a new --out folder");
    for (const auto& r : runs)
      if (r.iteration == iteration.get<int>() && r.point == point.get<int>()) answer.run = &r;
    if (!answer.run || !answer.run->ok)
      throw std::runtime_error("study store '" + store_name + "': the stored answer, run " +
                               std::to_string(iteration.get<int>()) + "/" + std::to_string(point.get<int>()) + ", is " +
                               (answer.run ? "a failed run" : "missing") +
                               "; restore study.db from a copy or rerun the study into a new --out folder");
    answer.finished = true;
    const nlohmann::json selection = result->value("final_selection", nlohmann::json());
    answer.why = selection.is_object() && selection.contains("fallback")
                     ? "the study's answer (" + selection.at("fallback").get<std::string>() + ")"
                     : "the study's answer, chosen by its final_selection";
    return answer;
  }
  for (const auto& r : runs)
    if (r.ok && (!answer.run || r.objective < answer.run->objective)) answer.run = &r;
  if (answer.run) answer.why = "the study has not finished: the lowest run so far, not a final answer";
  return answer;
}

}  // namespace demfit::identify
