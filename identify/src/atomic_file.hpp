#pragma once
// Internal: write a whole file through a temporary name and rename it into place, so a reader
// (or a killed run) never sees a half-written result file.
#include <filesystem>
#include <string>

namespace demfit::identify::detail {

void write_file_atomically(const std::filesystem::path& path, const std::string& content);

}  // namespace demfit::identify::detail
