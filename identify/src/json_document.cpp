#include "demfit/identify/json_document.hpp"

#include "demfit/identify/safe_output.hpp"

#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace demfit::identify {
namespace {

// Line of byte `offset` (1-based), for messages.
int line_of(const std::string& text, std::size_t offset) {
  int line = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) line += text[i] == '\n';
  return line;
}

// Nesting depth check on the raw text (strings skipped), before the parser builds anything.
void check_depth(const std::string& text, const std::string& source) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"')
      in_string = true;
    else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw std::runtime_error(source + ": line " + std::to_string(line_of(text, i)) + ": nested deeper than " +
                                 std::to_string(kMaxJsonDepth) +
                                 " levels; demfit inputs are at most a few levels deep");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

std::string one_line(std::string text, std::size_t limit) {
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';
  if (text.size() > limit) text = text.substr(0, limit) + "...";
  return text;
}

}  // namespace

std::string json_excerpt(const nlohmann::json& value) {
  if (value.is_object()) return "{...}";
  if (value.is_array()) return "[...]";
  return one_line(value.dump(), 40);
}

nlohmann::json parse_json_document(const std::string& text, const std::string& source) {
  if (text.size() > kMaxJsonBytes)
    throw std::runtime_error(source + ": " + std::to_string(text.size()) + " bytes, above the limit of " +
                             std::to_string(kMaxJsonBytes) + " bytes for a JSON input");
  check_depth(text, source);
  std::vector<std::set<std::string>> keys;
  std::string duplicate;
  const auto callback = [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    switch (event) {
      case nlohmann::json::parse_event_t::object_start:
        keys.emplace_back();
        break;
      case nlohmann::json::parse_event_t::object_end:
        if (!keys.empty()) keys.pop_back();
        break;
      case nlohmann::json::parse_event_t::key:
        if (!keys.empty() && !keys.back().insert(parsed.get<std::string>()).second && duplicate.empty())
          duplicate = parsed.get<std::string>();
        break;
      default:
        break;
    }
    return true;
  };
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(text, callback);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::runtime_error(source + " is not valid JSON (line " +
                             std::to_string(line_of(text, e.byte ? e.byte - 1 : 0)) + "): " + one_line(e.what(), 160));
  } catch (const nlohmann::json::exception& e) {
    // e.g. a number beyond double range (1e999): found by fuzz/fuzz_readers.
    throw std::runtime_error(source + " is not valid JSON: " + one_line(e.what(), 160));
  }
  if (!duplicate.empty())
    throw std::runtime_error(source + ": key '" + one_line(duplicate, 40) +
                             "' appears twice in one object; keep one (JSON keeps only the last, silently)");
  return json;
}

nlohmann::json read_json_file(const std::filesystem::path& path, const std::string& what) {
  const std::string source = what + " " + quote_path(path);
  // A regular file of at most kMaxJsonBytes: a device such as /dev/zero is refused unread.
  return parse_json_document(read_input_file(path, kMaxJsonBytes, source), source);
}

}  // namespace demfit::identify
