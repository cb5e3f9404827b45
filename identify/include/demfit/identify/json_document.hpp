#pragma once
// Reading JSON input with limits, for study files, case files and stored studies:
//   - at most kMaxJsonBytes bytes and kMaxJsonDepth nested arrays/objects (a deeply nested value
//     once crashed demfit with a stack overflow while formatting an error),
//   - a key given twice in one object is an error (the JSON library would keep the last silently),
//   - a UTF-8 byte-order mark is accepted,
//   - errors are one line, naming the source, with at most a short excerpt of the text.
#include <cstddef>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace demfit::identify {

inline constexpr std::size_t kMaxJsonBytes = 64u << 20;  // 64 MiB
inline constexpr int kMaxJsonDepth = 64;

// `source` names the input in errors, e.g. "study file 'a.json'".
nlohmann::json parse_json_document(const std::string& text, const std::string& source);
// Reads and parses a file; `what` is e.g. "study file" or "case file".
nlohmann::json read_json_file(const std::filesystem::path& path, const std::string& what);
// A value for an error message: scalars as JSON text cut to ~40 characters, "{...}" / "[...]"
// for objects and arrays (never the whole document).
std::string json_excerpt(const nlohmann::json& value);

}  // namespace demfit::identify
