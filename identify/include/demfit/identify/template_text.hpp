#pragma once
// Input files written from a template: the text with every placeholder {{name}} replaced by the
// value of the parameter `name`. Names are identifiers ([A-Za-z_][A-Za-z0-9_]*, at most 64
// characters); values are numbers demfit formats itself (shortest text that reads back as the
// same double), so no study value can add text of its own to an input file.
#include <map>
#include <string>
#include <vector>

namespace demfit::identify {

// One placeholder occurrence: the parameter it names and the 1-based line it is on.
struct Placeholder {
  std::string name;
  int line = 0;
};

// True for [A-Za-z_][A-Za-z0-9_]* of at most 64 characters.
bool is_parameter_identifier(const std::string& name);

// Every placeholder of `text`, in order. Throws std::runtime_error "<what> line N: ..." for a
// "{{" that does not open a well-formed placeholder ("{{ name }}", "{{1x}}", "{{a" without "}}").
std::vector<Placeholder> template_placeholders(const std::string& text, const std::string& what);

// The shortest decimal text that reads back as exactly `value` (std::to_chars); throws for a
// value that is not finite (an input file never receives "nan" or "inf").
std::string round_trip_number(double value);

// `text` with each {{name}} replaced by round_trip_number(values.at(name)). Throws
// std::runtime_error naming the placeholder when a name has no value.
std::string substitute_template(const std::string& text, const std::map<std::string, double>& values,
                                const std::string& what);

}  // namespace demfit::identify
