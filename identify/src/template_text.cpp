// Template substitution for external-program input files (template_text.hpp).
#include "demfit/identify/template_text.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>

namespace demfit::identify {
namespace {

constexpr std::size_t kMaxIdentifier = 64;

// The placeholder starting at text[open] ("{{"): its name and the index just past "}}".
struct Scanned {
  std::string name;
  std::size_t end = 0;
};

Scanned scan_placeholder(const std::string& text, std::size_t open, int line, const std::string& what) {
  const std::size_t close = text.find("}}", open + 2);
  const std::size_t newline = text.find('\n', open);
  if (close == std::string::npos || (newline != std::string::npos && newline < close))
    throw std::runtime_error(what + " line " + std::to_string(line) +
                             ": '{{' without a closing '}}' on the same line; write placeholders as {{name}}");
  std::string name = text.substr(open + 2, close - open - 2);
  if (!is_parameter_identifier(name)) {
    if (name.size() > kMaxIdentifier) name = name.substr(0, kMaxIdentifier) + "...";
    throw std::runtime_error(what + " line " + std::to_string(line) + ": '{{" + name +
                             "}}' is not a placeholder; write {{name}} with a parameter name of letters, digits and "
                             "'_' (no spaces, not starting with a digit)");
  }
  return {name, close + 2};
}

int count_lines(const std::string& text, std::size_t from, std::size_t to) {
  int lines = 0;
  for (std::size_t i = from; i < to; ++i) lines += text[i] == '\n';
  return lines;
}

}  // namespace

bool is_parameter_identifier(const std::string& name) {
  if (name.empty() || name.size() > kMaxIdentifier) return false;
  if (!(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_')) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

std::vector<Placeholder> template_placeholders(const std::string& text, const std::string& what) {
  std::vector<Placeholder> out;
  int line = 1;
  std::size_t at = 0;
  for (std::size_t open = text.find("{{"); open != std::string::npos; open = text.find("{{", at)) {
    line += count_lines(text, at, open);
    const Scanned s = scan_placeholder(text, open, line, what);
    out.push_back({s.name, line});
    at = s.end;
  }
  return out;
}

std::string round_trip_number(double value) {
  if (!std::isfinite(value)) throw std::runtime_error("a parameter value is not finite; it cannot be written to an input file");
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  if (error != std::errc()) throw std::runtime_error("a parameter value could not be formatted");
  return std::string(buffer, end);
}

std::string substitute_template(const std::string& text, const std::map<std::string, double>& values,
                                const std::string& what) {
  std::string out;
  out.reserve(text.size() + 64);
  int line = 1;
  std::size_t at = 0;
  for (std::size_t open = text.find("{{"); open != std::string::npos; open = text.find("{{", at)) {
    line += count_lines(text, at, open);
    const Scanned s = scan_placeholder(text, open, line, what);
    const auto found = values.find(s.name);
    if (found == values.end())
      throw std::runtime_error(what + " line " + std::to_string(line) + ": {{" + s.name + "}} has no value");
    out.append(text, at, open - at);
    out += round_trip_number(found->second);
    at = s.end;
  }
  out.append(text, at, std::string::npos);
  return out;
}

}  // namespace demfit::identify
