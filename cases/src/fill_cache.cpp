// On-disk cache of settled fills (see fill_cache.hpp).
#include "demfit/cases/fill_cache.hpp"

#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>

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

bool read_fill(const std::filesystem::path& path, const std::string& key_text, Fill& fill) {
  std::ifstream in(path);
  if (!in) return false;
  std::string line;
  if (!std::getline(in, line) || line != key_text) return false;  // hash collision or old format
  Fill out;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::array<double, 4> v{};
    std::istringstream fields(line);
    std::string token;
    for (double& x : v) {
      if (!(fields >> token)) return false;
      x = std::strtod(token.c_str(), nullptr);
    }
    out.positions.push_back({v[0], v[1], v[2]});
    out.radii.push_back(v[3]);
  }
  fill = std::move(out);
  return !fill.radii.empty();
}

void write_fill(const std::filesystem::path& path, const std::string& key_text, const Fill& fill) {
  // Hexadecimal floats (%a): the cached fill reads back bit-identical. Written through the one
  // atomic writer (issue #13), so a concurrent reader never sees a half-written fill.
  std::string text = key_text + '\n';
  char line[160];
  for (std::size_t i = 0; i < fill.radii.size(); ++i) {
    std::snprintf(line, sizeof line, "%a %a %a %a\n", fill.positions[i][0], fill.positions[i][1], fill.positions[i][2],
                  fill.radii[i]);
    text += line;
  }
  try {
    identify::write_file_atomically(path, text);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string(e.what()) + " (fill cache: set DEMFIT_CACHE_DIR to a writable folder)");
  }
}

}  // namespace

std::uint64_t fill_key_hash(const nlohmann::json& key) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : key.dump()) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

std::filesystem::path fill_cache_path(const std::filesystem::path& cache_dir, const std::string& prefix,
                                      const nlohmann::json& key) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fill_key_hash(key)));
  return cache_dir / (prefix + "_" + hex + ".fill");
}

Fill cached_fill(const std::filesystem::path& cache_dir, const std::string& prefix, const nlohmann::json& key,
                 const std::function<Fill()>& generate, bool* generated) {
  const std::filesystem::path path = fill_cache_path(cache_dir, prefix, key);
  const std::string key_text = key.dump();
  std::lock_guard<std::mutex> lock(file_mutex(path.string()));
  if (generated) *generated = false;
  Fill fill;
  if (read_fill(path, key_text, fill)) return fill;
  fill = generate();
  write_fill(path, key_text, fill);
  if (generated) *generated = true;
  return fill;
}

}  // namespace demfit::cases
