#pragma once
// Internal: write a whole file through a temporary name beside it and rename it into place, so a
// reader (or a killed run) never sees a half-written file. (imaging must not depend on identify,
// which has its own copy of this idea.)
#include <filesystem>
#include <string>

namespace demfit::imaging::detail {

void write_file_atomically(const std::filesystem::path& path, const std::string& content);

}  // namespace demfit::imaging::detail
