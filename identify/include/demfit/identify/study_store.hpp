#pragma once
// The study store: one SQLite file beside the results holding the resolved study, every
// evaluation (committed as it finishes) and every iteration. It is what --resume replays and
// what `demfit report` / `demfit export` read. Tables (schema version kStoreSchemaVersion):
//   meta(key, value, checksum)  schema_version, study_hash, study_json, result_json
//   evaluations(iteration, point, kind, unit_x, parameters, curves, objective, wall_seconds,
//               status, error, checksum)  one row per run; (iteration, point) is unique
//   iterations(iteration, record, checksum)  region, predicted optimum and objectives, JSON
// Every row carries a checksum of its stored texts (FNV-1a 64); a row that no longer matches it
// was edited or damaged, and reading the store stops with an error naming the row.
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/identify/model.hpp"
#include "demfit/identify/study_spec.hpp"

struct sqlite3;

namespace demfit::identify {

inline constexpr int kStoreSchemaVersion = 2;
// The iteration number under which the runs of a study's cheap level are stored (study_spec.hpp
// CheapLevelSpec): before iteration 0, and apart from the study's own runs.
inline constexpr int kCheapLevelIteration = -1;

struct EvaluationRecord {
  int iteration = 0;
  int point = 0;               // index within the iteration's batch
  std::string kind;            // "initial", "design", "optimum", "verification"
  std::vector<double> unit_x;  // varied variables in unit coordinates [0, 1]
  ParameterSet parameters;     // everything passed to the model
  CurveSet curves;             // empty when failed
  double objective = 0.0;      // composite objective (NaN when failed)
  double wall_seconds = 0.0;
  bool ok = false;
  std::string error;
};

struct IterationRecord {
  int iteration = 0;
  std::vector<double> region_center;      // unit coordinates
  std::vector<double> region_range;       // unit coordinates (full box = 1)
  std::vector<double> predicted_optimum;  // unit coordinates
  ParameterSet predicted_parameters;      // physical values of the varied variables
  double predicted_objective = 0.0;       // surrogate's value at the predicted optimum
  double best_objective = 0.0;            // best evaluated objective so far
  int runs_done = 0;
  double design_change = 0.0;     // max |change| of the optimum, fraction of range
  double objective_change = 0.0;  // relative change of the predicted objective
};

nlohmann::json to_json(const EvaluationRecord& record);
nlohmann::json to_json(const IterationRecord& record);

class StudyStore {
 public:
  // Opens path for running `spec`. A missing file is created. An existing file is refused
  // unless resume is true, and then also when it belongs to another study or schema version.
  // resolved_model (if not null) is recorded, or on resume compared with the recorded one.
  static StudyStore open_for_run(const std::filesystem::path& path, const StudySpec& spec, bool resume,
                                 const nlohmann::json& resolved_model = nlohmann::json());
  // Opens an existing store for reading (report, export); refuses another schema version.
  static StudyStore open_existing(const std::filesystem::path& path);

  StudyStore(StudyStore&&) noexcept;
  StudyStore& operator=(StudyStore&&) noexcept;
  ~StudyStore();

  nlohmann::json study_json() const;
  // What the study simulated, as recorded when it started (for a DEM case the case with every
  // default filled in); nullopt when the store holds none.
  std::optional<nlohmann::json> resolved_model() const;
  // Commits one evaluation (replacing a row with the same iteration and point).
  void add_evaluation(const EvaluationRecord& record);
  const EvaluationRecord* find_evaluation(int iteration, int point) const;
  // The study model's runs, ordered by (iteration, point); the cheap level's are not among them.
  std::vector<EvaluationRecord> evaluations() const;
  // The cheap level's runs (iteration kCheapLevelIteration), ordered by point.
  std::vector<EvaluationRecord> cheap_evaluations() const;
  void put_iteration(const IterationRecord& record);
  std::vector<IterationRecord> iterations() const;  // ordered by iteration
  void put_result(const nlohmann::json& result);
  std::optional<nlohmann::json> result() const;
  const std::filesystem::path& path() const { return path_; }

 private:
  StudyStore(sqlite3* db, std::filesystem::path path);
  void execute(const std::string& sql);
  void put_meta(const std::string& key, const std::string& value);
  std::optional<std::string> meta(const std::string& key) const;
  void load();
  static void check_same_model(StudyStore& store, const nlohmann::json& resolved_model);

  sqlite3* db_ = nullptr;
  std::filesystem::path path_;
  std::map<std::pair<int, int>, EvaluationRecord> evaluations_;
  std::map<int, IterationRecord> iterations_;
};

}  // namespace demfit::identify
