#pragma once
// One process per study store: two `identify --resume` on one study would both run
// every missing run. The lock is an flock(2) on <folder>/.demfit-lock, held for the object's
// life and released by the kernel when the process ends (a killed run leaves no stale lock).
#include <filesystem>
#include <optional>
#include <string_view>

#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/study.hpp"

namespace demfit::identify {

class StoreLock {
 public:
  // Throws std::runtime_error (one line, naming the store) when another process holds the lock.
  explicit StoreLock(const std::filesystem::path& folder);
  ~StoreLock();
  StoreLock(const StoreLock&) = delete;
  StoreLock& operator=(const StoreLock&) = delete;

 private:
  int fd_ = -1;
};

// A study run's claim on its output folder, before any work: the output-folder rules
// (safe_output.hpp), then the lock when the folder exists (a second run on one study fails at
// once), then an existing study.db without options.resume is refused with `resume_hint` (how this
// front end asks to resume: "--resume", "resume=True").
void claim_study_folder(const RunOptions& options, const OutputRequest& request, std::optional<StoreLock>& lock,
                        std::string_view resume_hint);

}  // namespace demfit::identify
