// On-disk cache of settled fills (see fill_cache.hpp).
#include "demfit/cases/fill_cache.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "demfit/identify/fnv_hash.hpp"
#include "demfit/identify/safe_output.hpp"

namespace demfit::cases {
namespace {

std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}

// One mutex per cache file, so concurrent evaluations wait for a fill being generated.
std::mutex& file_mutex(const std::string& path) {
  static std::map<std::string, std::unique_ptr<std::mutex>> mutexes;
  std::lock_guard<std::mutex> lock(registry_mutex());
  auto& slot = mutexes[path];
  if (!slot) slot = std::make_unique<std::mutex>();
  return *slot;
}

// FNV-1a 64 of the particle lines: a cached fill cut short, edited or damaged no longer matches
// the count and checksum its last line carries, and is generated again.
// The cache's own FNV start value (its first digits only, as the keys of fills already cached were
// computed): kept so those keys stay valid.
constexpr std::uint64_t kFillHashStart = 1469598103934665603ULL;

std::uint64_t text_checksum(const std::string& text) { return identify::fnv1a64(text, kFillHashStart); }

// A whole token as a finite number, or nothing (no silent 0 for garbage, no "0.5abc").
bool parse_number(const std::string& token, double& value) {
  char* end = nullptr;
  value = std::strtod(token.c_str(), &end);
  return end != token.c_str() && *end == '\0' && std::isfinite(value);
}

bool parse_body(const std::string& body, Fill& out) {
  std::istringstream lines(body);
  std::string line;
  while (std::getline(lines, line)) {
    std::array<double, 4> v{};
    std::istringstream fields(line);
    std::string token;
    for (double& x : v)
      if (!(fields >> token) || !parse_number(token, x)) return false;
    if (fields >> token || !(v[3] > 0.0)) return false;  // four fields, a positive radius
    out.positions.push_back({v[0], v[1], v[2]});
    out.radii.push_back(v[3]);
  }
  return true;
}

bool read_fill(const std::filesystem::path& path, const std::string& key_text, Fill& fill) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::string line;
  if (!std::getline(in, line) || line != key_text) return false;  // hash collision or old format
  std::ostringstream rest;
  rest << in.rdbuf();
  const std::string text = rest.str();
  // The last line: "end <count> <checksum>"; the body is everything before it.
  const std::size_t trailer = text.rfind("end ");
  if (trailer == std::string::npos || (trailer > 0 && text[trailer - 1] != '\n')) return false;
  const std::string body = text.substr(0, trailer);
  std::size_t count = 0;
  unsigned long long checksum = 0;
  char tail = 0;
  if (std::sscanf(text.c_str() + trailer, "end %zu %llx%c", &count, &checksum, &tail) != 3 || tail != '\n')
    return false;
  if (checksum != text_checksum(body)) return false;
  Fill out;
  if (!parse_body(body, out) || out.radii.size() != count || count == 0) return false;
  fill = std::move(out);
  return true;
}

void write_fill(const std::filesystem::path& path, const std::string& key_text, const Fill& fill) {
  // Hexadecimal floats (%a): the cached fill reads back bit-identical. Written through the one
  // atomic writer, so a concurrent reader never sees a half-written fill.
  std::string body;
  char line[160];
  for (std::size_t i = 0; i < fill.radii.size(); ++i) {
    std::snprintf(line, sizeof line, "%a %a %a %a\n", fill.positions[i][0], fill.positions[i][1], fill.positions[i][2],
                  fill.radii[i]);
    body += line;
  }
  std::snprintf(line, sizeof line, "end %zu %016llx\n", fill.radii.size(),
                static_cast<unsigned long long>(text_checksum(body)));
  try {
    identify::write_file_atomically(path, key_text + '\n' + body + line);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string(e.what()) + " (fill cache: set DEMFIT_CACHE_DIR to a writable folder)");
  }
}

}  // namespace

std::uint64_t fill_key_hash(const nlohmann::json& key) { return text_checksum(key.dump()); }

std::filesystem::path fill_cache_path(const std::filesystem::path& cache_dir, const std::string& prefix,
                                      const nlohmann::json& key) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fill_key_hash(key)));
  return cache_dir / (prefix + "_" + hex + ".fill");
}

Fill cached_fill(const std::filesystem::path& cache_dir, const std::string& prefix, const nlohmann::json& key,
                 const std::function<Fill()>& generate, bool* generated,
                 const std::function<bool(const Fill&)>& plausible) {
  const std::filesystem::path path = fill_cache_path(cache_dir, prefix, key);
  const std::string key_text = key.dump();
  std::lock_guard<std::mutex> lock(file_mutex(path.string()));
  if (generated) *generated = false;
  Fill fill;
  if (read_fill(path, key_text, fill) && (!plausible || plausible(fill))) return fill;
  // Missing, damaged or implausible (a particle outside the container): generated again.
  fill = generate();
  write_fill(path, key_text, fill);
  if (generated) *generated = true;
  return fill;
}

}  // namespace demfit::cases
