#pragma once
// Internal: the one atomic writer (public in demfit/identify/safe_output.hpp), kept under its old
// name for the identify sources.
#include <filesystem>
#include <string>

#include "demfit/identify/safe_output.hpp"

namespace demfit::identify::detail {

inline void write_file_atomically(const std::filesystem::path& path, const std::string& content) {
  identify::write_file_atomically(path, content);
}

}  // namespace demfit::identify::detail
