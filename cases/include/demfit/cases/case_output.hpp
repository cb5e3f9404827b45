#pragma once
// Writing a case run to disk, all-or-nothing: results go to a staging folder next to the target
// and are renamed into place at the end; on failure the staging folder is removed, so bad input
// or a failed run leaves no partial output behind.
#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "demfit/cases/case_runner.hpp"

namespace demfit::cases {

class StagedDirectory {
 public:
  // Does not touch the file system until path() is first used.
  explicit StagedDirectory(std::filesystem::path target);
  ~StagedDirectory();  // removes the staging folder unless committed
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;
  // The staging folder (created on first call).
  const std::filesystem::path& path();
  // Replaces `target` (removing an existing one) by the staging folder.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path staging_;
  bool created_ = false;
  bool committed_ = false;
};

struct SyntheticNoise {
  double relative = 0.0;   // sigma = relative * max|y| per curve; 0 = no noise (not synthetic-labelled)
  std::uint64_t seed = 0;  // curve k (in name order) uses seed + k
};

// Writes <dir>/<curve>.csv for every curve (with '#' comment lines: case, parameters, and a
// SYNTHETIC label when noise is added), <dir>/<table>.csv for every table, <dir>/case_resolved.json
// and <dir>/summary.txt. `parameters` are the evaluated parameters (recorded in the comments).
void write_case_result(const std::filesystem::path& dir, const CaseResult& result, const nlohmann::json& resolved_case,
                       const identify::ParameterSet& parameters, const SyntheticNoise& noise);

// Human-readable summary: the summary lines and, for each curve, a short table of points.
std::string format_summary(const CaseResult& result, int points_per_curve = 11);

}  // namespace demfit::cases
