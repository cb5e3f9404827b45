// The settled-fill cache (fill_cache.hpp) uses a cached file only when it is whole and plausible:
// a fill cut short, a garbage number, or a particle outside the container is generated again,
// never read as a smaller or wrong bed.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "demfit/cases/fill_cache.hpp"

namespace {
namespace fs = std::filesystem;
using demfit::cases::cached_fill;
using demfit::cases::Fill;

Fill lattice(int count) {
  Fill f;
  for (int i = 0; i < count; ++i) {
    f.positions.push_back({0.001 * (i % 5), 0.001 * (i / 5), 0.0005 + 0.001 * (i % 3)});
    f.radii.push_back(0.0004 + 1e-6 * i);
  }
  return f;
}

struct CacheDir {
  fs::path dir;
  nlohmann::json key = {{"case", "test"}, {"count", 141}};
  explicit CacheDir(const std::string& name) : dir(fs::temp_directory_path() / ("demfit_fill_cache_" + name)) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~CacheDir() { fs::remove_all(dir); }
  fs::path file() const { return demfit::cases::fill_cache_path(dir, "t", key); }
  // The fill through the cache, and whether it had to be generated.
  std::pair<Fill, bool> get(const std::function<bool(const Fill&)>& plausible = {}) const {
    bool generated = false;
    Fill f = cached_fill(dir, "t", key, [] { return lattice(141); }, &generated, plausible);
    return {f, generated};
  }
  std::string text() const {
    std::ifstream in(file(), std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  void write(const std::string& text) const { std::ofstream(file(), std::ios::binary | std::ios::trunc) << text; }
};

bool same(const Fill& a, const Fill& b) { return a.positions == b.positions && a.radii == b.radii; }

}  // namespace

TEST_CASE("a cached fill reads back bit-identical and is not generated twice") {
  CacheDir c("round_trip");
  const auto [first, generated_first] = c.get();
  const auto [second, generated_second] = c.get();
  CHECK(generated_first);
  CHECK_FALSE(generated_second);
  CHECK(same(first, lattice(141)));
  CHECK(same(second, lattice(141)));
}

TEST_CASE("a cached fill cut in half is generated again, not read as a smaller bed") {
  CacheDir c("truncated");
  c.get();
  const std::string text = c.text();
  c.write(text.substr(0, text.size() / 2));
  const auto [fill, generated] = c.get();
  CHECK(generated);
  CHECK(fill.radii.size() == 141);
}

TEST_CASE("a cached fill with a garbage number is generated again, not read as 0") {
  CacheDir c("garbage");
  c.get();
  std::string text = c.text();
  const std::size_t line = text.find('\n', text.find('\n') + 1) + 1;  // the second particle's line
  text.replace(line, 4, "zzzz");
  c.write(text);
  const auto [fill, generated] = c.get();
  CHECK(generated);
  CHECK(same(fill, lattice(141)));
}

TEST_CASE("a cached fill with one value changed but well formed fails its checksum and is generated again") {
  CacheDir c("edited");
  c.get();
  std::string text = c.text();
  const std::size_t second_line = text.find('\n') + 1;
  const std::size_t p = text.find("0x1", second_line);
  REQUIRE(p != std::string::npos);
  text[p + 2] = '0';  // 0x1.… becomes 0x0.…: a valid hexadecimal float, another value
  c.write(text);
  const auto [fill, generated] = c.get();
  CHECK(generated);
  CHECK(same(fill, lattice(141)));
}

TEST_CASE("a cached fill the case finds implausible (a particle outside the container) is generated again") {
  CacheDir c("implausible");
  c.get();
  int checks = 0;
  const auto inside = [&](const Fill& f) {
    ++checks;
    return f.positions.front()[0] < 1.0;  // the cached one passes; see below for one that does not
  };
  CHECK_FALSE(c.get(inside).second);
  const auto never = [](const Fill&) { return false; };
  CHECK(c.get(never).second);
  CHECK(checks == 1);
}
