#pragma once
// Shared checks of the command line: thread counts capped at the machine's cores, numbers that
// are the whole text or an error, finite numeric options, the input files of a study (which no
// output may replace), and the removal of staging folders left by killed runs.
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "demfit/identify/study_spec.hpp"

namespace demfit::apps {

// `requested` capped at the cores this process may use, with a note on stderr when capped.
int capped_threads(int requested, const std::string& option);
// Throws "<option>: must be a finite number" for NaN or infinity.
void require_finite(double value, const std::string& option);
// The number `text` is, when it is one finite number and nothing else ("0,3" and "0.5abc" are
// errors, not 0 and 0.5); throws "<field>: '<text>' is not a number; ..." otherwise.
double parse_number(const std::string& text, const std::string& field);
// A whole non-negative integer ("-1" and "1e3" are errors) at most `max`.
unsigned long long parse_count(const std::string& text, const std::string& field, unsigned long long max);
// Throws "<option>: <value> is above the limit of <max>; <why>" when value > max.
void require_at_most(long long value, long long max, const std::string& option, const std::string& why);
// CLI11 check of a path option: the empty string is an error, not "the default".
CLI::Validator non_empty_path();
// The folders above `target` that do not exist yet. Unless keep() is called, the destructor removes
// those that are still empty, so a failed run leaves no empty "results/" behind.
class CreatedParents {
 public:
  explicit CreatedParents(const std::filesystem::path& target);
  ~CreatedParents();
  CreatedParents(const CreatedParents&) = delete;
  CreatedParents& operator=(const CreatedParents&) = delete;
  void keep() { keep_ = true; }

 private:
  std::vector<std::filesystem::path> missing_;  // deepest first
  bool keep_ = false;
};

// Removes "<parent>/.<name>.partial-<pid>" staging folders of processes that no longer run.
void remove_stale_staging(const std::filesystem::path& target);

}  // namespace demfit::apps
