#include "demfit/identify/store_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace demfit::identify {

StoreLock::StoreLock(const std::filesystem::path& folder) {
  const std::filesystem::path path = folder / ".demfit-lock";
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw std::runtime_error("study store in '" + folder.string() + "': cannot create the lock file (" +
                             std::strerror(errno) + "); check the folder permissions");
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK)
      throw std::runtime_error(
          "study store '" + (folder / "study.db").string() +
          "' is in use by another demfit process; wait for it to finish or use another --out folder");
    throw std::runtime_error("study store in '" + folder.string() + "': cannot lock (" + std::strerror(error) + ")");
  }
}

StoreLock::~StoreLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the flock
}

void claim_study_folder(const RunOptions& options, const OutputRequest& request, std::optional<StoreLock>& lock,
                        std::string_view resume_hint) {
  check_output_folder(options.output_dir, request);
  if (!std::filesystem::is_directory(options.output_dir)) return;
  lock.emplace(options.output_dir);
  const std::filesystem::path db = options.output_dir / "study.db";
  std::error_code error;
  if (!options.resume && std::filesystem::exists(std::filesystem::symlink_status(db, error)))
    throw std::runtime_error("study store " + quote_path(db) + " already exists; pass " + std::string(resume_hint) +
                             " to continue it, or choose another output folder");
}

}  // namespace demfit::identify
