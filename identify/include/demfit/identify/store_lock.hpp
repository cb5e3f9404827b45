#pragma once
// One process per study store: two `identify --resume` on one study would both run
// every missing run. The lock is an flock(2) on <folder>/.demfit-lock, held for the object's
// life and released by the kernel when the process ends (a killed run leaves no stale lock).
#include <filesystem>

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

}  // namespace demfit::identify
