// Seeded mutation fuzzer of demfit's input readers (issue #13): JSON documents (study and case
// files through their strict parsers) and curve CSV files. Compiled with the project (and with
// the sanitizers under scripts/sanitize); scripts/fuzz runs it for a bounded time.
//
//   fuzz_readers SECONDS [SEED] [OUT_DIR]
//
// Each execution mutates one of the seed inputs (byte flips, inserted JSON/CSV tokens, deleted and
// duplicated ranges) and feeds it to the readers. A reader may throw std::runtime_error (a clean
// one-line error) and nothing else: any other exception is a finding, saved to OUT_DIR. A crash
// (signal or sanitizer report) ends the process; OUT_DIR/current.input then holds the input.
// Prints "executions N crashes 0 findings F" at the end.
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "demfit/cases/case_spec.hpp"
#include "demfit/identify/curve_io.hpp"
#include "demfit/identify/json_document.hpp"
#include "demfit/identify/study_spec.hpp"

namespace {

const std::vector<std::string> kSeeds = {
    R"({"demfit_study_version": 1, "name": "fuzz", "model": {"case": "analytic", "overrides": {"points": 11},
        "fixed_parameters": {"slope": 0.5}},
        "variables": [{"name": "amplitude", "lower": 0.5, "upper": 2.0, "initial": 1.0},
                      {"name": "rate", "lower": 1.0, "upper": 8.0, "log_scale": true, "initial_range": 0.5}],
        "targets": [{"curve": "response", "name": "t", "x_column": "x_1", "y_column": "y_1",
                     "x": [0, 0.25, 0.5, 1.0], "y": [0, 0.5, 0.8, 1.5], "metric": "mse", "weight": 2}],
        "sampling": {"points_per_iteration": 6, "strategy": "srsm"},
        "domain_reduction": {"gamma_pan": 1.0, "gamma_osc": 0.6, "eta": 0.8},
        "surrogate": {"basis": "gaussian", "responses": "curve_points", "smoothing": 0},
        "stopping": {"max_iterations": 5, "design_tolerance": 0.01, "objective_tolerance": 0.001}, "seed": 3})",
    R"({"case": "pellet_compression", "particle": {"radius": 0.001, "density": 1500},
        "pellet": {"count": 200, "piston_speed": 0.05}, "contact": {"normk": 0.01}})",
    R"({"case": "rotary_drum", "drum": {"coarse_graining": "scg", "scale_factor": 2, "duration": 0.5}})",
    "# comment\nx_1,y_1\n0,0\n0.25,0.5\n0.5,0.8\n1.0,1.5\n",
    "\xEF\xBB\xBFvolume_cm3,pressure_MPa,extra\n\"20.0\",0.0,a\n19.5,+1e-3,b\n19.0,2.5e+00,c\n",
};

const std::vector<std::string> kTokens = {"[",
                                          "]",
                                          "{",
                                          "}",
                                          "\"",
                                          ",",
                                          ":",
                                          "\n",
                                          "\\",
                                          "\\u0000",
                                          "1e999",
                                          "-0",
                                          "nan",
                                          "null",
                                          "true",
                                          "\"name\":",
                                          "\"x\":[",
                                          "\xEF\xBB\xBF",
                                          "#",
                                          "\r",
                                          "18446744073709551616",
                                          "-9223372036854775809",
                                          "1e-400",
                                          "\"\":",
                                          "x_1",
                                          "y_1",
                                          ",,,,",
                                          "\x00",
                                          "\xff\xfe",
                                          "[[[[[[[[[[[[",
                                          "]]]]]]]]"};

std::string mutate(std::string text, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) { return n == 0 ? std::size_t{0} : static_cast<std::size_t>(rng() % n); };
  const int steps = 1 + static_cast<int>(rng() % 8);
  for (int s = 0; s < steps; ++s) {
    const std::size_t at = pick(text.size() + 1);
    switch (rng() % 6) {
      case 0:
        if (!text.empty()) text[pick(text.size())] ^= static_cast<char>(1u << (rng() % 8));
        break;
      case 1:
        text.insert(at, kTokens[pick(kTokens.size())]);
        break;
      case 2:
        text.erase(at, pick(16));
        break;
      case 3: {
        const std::size_t from = pick(text.size() + 1);
        text.insert(at, text.substr(from, pick(64)));
        break;
      }
      case 4:
        text.insert(at, 1, static_cast<char>(rng() & 0xff));
        break;
      default:
        if (!text.empty()) text.resize(pick(text.size()));
        break;
    }
  }
  if (text.size() > (1u << 16)) text.resize(1u << 16);
  return text;
}

// One execution: every reader on the text. Returns "" or the name of an unexpected exception.
std::string execute(const std::string& text) {
  try {
    try {
      const nlohmann::json json = demfit::identify::parse_json_document(text, "fuzz input");
      try {
        demfit::identify::parse_study(json, "/nonexistent-fuzz-folder");
      } catch (const std::runtime_error&) {}
      try {
        demfit::cases::parse_case(json);
      } catch (const std::runtime_error&) {}
    } catch (const std::runtime_error&) {}
    try {
      std::istringstream in(text);
      demfit::identify::parse_curve_csv(in, "fuzz.csv", "x_1", "y_1");
    } catch (const std::runtime_error&) {}
  } catch (const std::exception& e) { return std::string("unexpected exception: ") + e.what(); }
  return {};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: fuzz_readers SECONDS [SEED] [OUT_DIR]\n");
    return 2;
  }
  const double seconds = std::stod(argv[1]);
  const std::uint64_t seed = argc > 2 ? std::stoull(argv[2]) : 1;
  const std::filesystem::path out = argc > 3 ? argv[3] : "fuzz-findings";
  std::filesystem::create_directories(out);
  const int current = ::open((out / "current.input").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::mt19937_64 rng(seed);
  const auto start = std::chrono::steady_clock::now();
  long executions = 0, findings = 0;
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < seconds) {
    for (int batch = 0; batch < 64; ++batch) {
      const std::string input = mutate(kSeeds[rng() % kSeeds.size()], rng);
      if (current >= 0 && ::ftruncate(current, 0) == 0)
        if (::pwrite(current, input.data(), input.size(), 0) < 0) return 3;
      const std::string problem = execute(input);
      ++executions;
      if (!problem.empty()) {
        ++findings;
        std::ofstream(out / ("finding-" + std::to_string(findings) + ".input"), std::ios::binary) << input;
        std::fprintf(stderr, "finding %ld: %s\n", findings, problem.substr(0, 200).c_str());
      }
    }
  }
  if (current >= 0) ::close(current);
  std::filesystem::remove(out / "current.input");
  std::printf("executions %ld crashes 0 findings %ld (seed %llu, %.0f s)\n", executions, findings,
              static_cast<unsigned long long>(seed), seconds);
  return findings == 0 ? 0 : 1;
}
