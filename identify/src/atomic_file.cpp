#include "atomic_file.hpp"

#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace demfit::identify::detail {

void write_file_atomically(const std::filesystem::path& path, const std::string& content) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  // The pid keeps concurrent writers (tests in parallel) from sharing a temporary.
  std::filesystem::path temporary = path;
  temporary += ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write '" + temporary.string() + "'; check the folder permissions");
    out << content;
    out.flush();
    if (!out) throw std::runtime_error("writing '" + temporary.string() + "' failed; check free disk space");
  }
  std::filesystem::rename(temporary, path);
}

}  // namespace demfit::identify::detail
