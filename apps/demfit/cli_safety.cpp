#include "cli_safety.hpp"

#include "demfit/identify/safe_output.hpp"

#include <sched.h>
#include <signal.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <thread>

namespace demfit::apps {

int capped_threads(int requested, const std::string& option) {
  int cores = static_cast<int>(std::thread::hardware_concurrency());
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) cores = CPU_COUNT(&set);
  if (cores < 1) cores = 1;
  if (requested <= cores) return requested;
  std::fprintf(stderr, "demfit: note: %s %d is above the %d core(s) available; using %d\n", option.c_str(), requested,
               cores, cores);
  return cores;
}

void require_finite(double value, const std::string& option) {
  if (!std::isfinite(value)) throw std::runtime_error(option + ": must be a finite number");
}

namespace {
std::string excerpt(const std::string& text) {
  return "'" + identify::printable(text.size() > 40 ? text.substr(0, 40) + "..." : text) + "'";
}
}  // namespace

double parse_number(const std::string& text, const std::string& field) {
  double value = 0.0;
  const char* first = text.data();
  const char* last = first + text.size();
  if (first != last && *first == '+') ++first;  // from_chars takes no leading '+'
  const auto result = std::from_chars(first, last, value);
  if (text.empty() || result.ec == std::errc::invalid_argument || result.ptr != last)
    throw std::runtime_error(field + ": " + excerpt(text) +
                             " is not a number; give one number with a decimal point, e.g. 0.3 (no comma, no unit)");
  if (result.ec == std::errc::result_out_of_range || !std::isfinite(value))
    throw std::runtime_error(field + ": " + excerpt(text) + " is not a finite number in double range; give e.g. 0.3");
  return value;
}

unsigned long long parse_count(const std::string& text, const std::string& field, unsigned long long max) {
  unsigned long long value = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || result.ec == std::errc::invalid_argument || result.ptr != text.data() + text.size())
    throw std::runtime_error(field + ": " + excerpt(text) + " is not a whole number >= 0; give e.g. 1");
  if (result.ec == std::errc::result_out_of_range || value > max)
    throw std::runtime_error(field + ": " + excerpt(text) + " is above the limit of " + std::to_string(max));
  return value;
}

void require_at_most(long long value, long long max, const std::string& option, const std::string& why) {
  if (value > max)
    throw std::runtime_error(option + ": " + std::to_string(value) + " is above the limit of " + std::to_string(max) +
                             "; " + why);
}

CLI::Validator non_empty_path() {
  return CLI::Validator(
      [](std::string& value) {
        return value.empty() ? std::string("empty path; give a name (an empty value does not mean the default)")
                             : std::string();
      },
      "PATH");
}

CreatedParents::CreatedParents(const std::filesystem::path& target) {
  std::error_code error;
  for (std::filesystem::path p = target.parent_path(); !p.empty() && p != p.root_path(); p = p.parent_path()) {
    if (std::filesystem::exists(std::filesystem::symlink_status(p, error))) break;
    missing_.push_back(p);
  }
}

CreatedParents::~CreatedParents() {
  if (keep_) return;
  std::error_code error;
  for (const auto& p : missing_) std::filesystem::remove(p, error);  // removes only an empty folder
}

void remove_stale_staging(const std::filesystem::path& target) {
  std::filesystem::path t = target.filename().empty() ? target.parent_path() : target;
  const std::filesystem::path parent = t.parent_path().empty() ? std::filesystem::path(".") : t.parent_path();
  std::string prefix = ".";  // appended: GCC 12 warns (-Wrestrict) on "literal" + string
  prefix += t.filename().string();
  prefix += ".partial-";
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(parent, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::stol(digits);
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM) continue;  // still running
    if (!entry.is_directory(error) || entry.is_symlink(error)) continue;
    std::filesystem::remove_all(entry.path(), error);
  }
}

}  // namespace demfit::apps
