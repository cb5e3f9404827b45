#include "atomic_write.hpp"

#include <fstream>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace demfit::imaging::detail {

void write_file_atomically(const std::filesystem::path& path, const std::string& content) {
  // The pid keeps concurrent writers (tests in parallel) from sharing a temporary.
  std::filesystem::path temporary = path;
  temporary += ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write '" + temporary.string() + "'; check that the folder exists and is writable");
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      out.close();
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw std::runtime_error("writing '" + temporary.string() + "' failed; check free disk space");
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot rename '" + temporary.string() + "' to '" + path.string() + "': " + error.message());
  }
}

}  // namespace demfit::imaging::detail
