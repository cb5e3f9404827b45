// demfit target from-image end to end: a drawn photo gives free_surface.csv (x_mm,z_mm, drum frame)
// and overlay.png; bad input exits != 0 with one "demfit: error:" line and leaves no output folder.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <set>
#include <string>
#include <vector>

#include "demfit/imaging/image.hpp"
#include "drawn_images.hpp"

using namespace demfit::imaging;
namespace fs = std::filesystem;

namespace {

struct CliRun {
  int status = 0;
  std::string output, error;
};

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(DEMFIT_BINARY_DIR) / "test_imaging_cli_scratch" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

CliRun run_demfit(const std::string& arguments, const fs::path& dir) {
  const std::string command = std::string("'") + DEMFIT_EXE + "' " + arguments + " > '" +
                              (dir / "stdout.txt").string() + "' 2> '" + (dir / "stderr.txt").string() + "'";
  const int raw = std::system(command.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(dir / "stdout.txt"), slurp(dir / "stderr.txt")};
}

const auto kSurface = [](double x) { return 0.002 - std::tan(35.0 * M_PI / 180.0) * x; };

fs::path drawn_photo(const fs::path& dir) {
  test::write_png(dir / "photo.png", to_rgb(test::draw_surface(test::DrawnDrum{}, kSurface)));
  return dir / "photo.png";
}

}  // namespace

TEST_CASE("target from-image writes the profile in millimetres of the drum frame and an overlay") {
  const fs::path dir = scratch("ok");
  const fs::path photo = drawn_photo(dir);
  const CliRun run = run_demfit(
      "target from-image '" + photo.string() + "' --diameter 84mm --out '" + (dir / "out").string() + "'", dir);
  INFO("stderr: " << run.error);
  REQUIRE(run.status == 0);
  std::ifstream csv(dir / "out" / "free_surface.csv");
  std::string line;
  std::vector<std::string> comments;
  while (std::getline(csv, line) && line.rfind('#', 0) == 0) comments.push_back(line);
  CHECK(line == "x_mm,z_mm");
  REQUIRE(comments.size() >= 1u);
  CHECK(slurp(dir / "out" / "free_surface.csv").find("photo.png") != std::string::npos);
  const double h_mm = 84.0 / 405.0;
  int rows = 0;
  for (double x_mm, z_mm; std::getline(csv, line); ++rows) {
    REQUIRE(std::sscanf(line.c_str(), "%lf,%lf", &x_mm, &z_mm) == 2);
    CHECK(std::abs(z_mm - 1e3 * kSurface(x_mm * 1e-3)) < 0.5 * h_mm);
  }
  CHECK(rows == 41);
  const GreyImage overlay = read_grey_image(dir / "out" / "overlay.png");
  CHECK(overlay.width == 406);
  // Exactly the two files and demfit's output-folder marker: no temporaries left.
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir / "out")) names.insert(entry.path().filename().string());
  CHECK(names == std::set<std::string>{".demfit-output", "free_surface.csv", "overlay.png"});
}

TEST_CASE("target from-image with a truncated photo fails naming it and writes nothing") {
  const fs::path dir = scratch("truncated");
  const std::string png = slurp(drawn_photo(dir));
  std::ofstream(dir / "cut.png", std::ios::binary) << png.substr(0, png.size() / 2);
  const CliRun run = run_demfit(
      "target from-image '" + (dir / "cut.png").string() + "' --diameter 84mm --out '" + (dir / "out").string() + "'",
      dir);
  CHECK(run.status != 0);
  CHECK(run.error.rfind("demfit: error: ", 0) == 0);
  CHECK(run.error.find("cut.png") != std::string::npos);
  CHECK(std::count(run.error.begin(), run.error.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("target from-image with a diameter lacking its unit or an unknown unit fails naming --diameter") {
  const fs::path dir = scratch("diameter");
  const fs::path photo = drawn_photo(dir);
  for (const std::string diameter : {"84", "84cm", "-0.084m"}) {
    const CliRun run = run_demfit(
        "target from-image '" + photo.string() + "' --diameter " + diameter + " --out '" + (dir / "out").string() + "'",
        dir);
    INFO("--diameter " << diameter << ": " << run.error);
    CHECK(run.status != 0);
    CHECK(run.error.find("--diameter") != std::string::npos);
    CHECK(std::count(run.error.begin(), run.error.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(dir / "out"));
  }
  // 0.084 as a bare number is metres and works.
  CHECK(run_demfit("target from-image '" + photo.string() + "' --diameter 0.084 --out '" + (dir / "out").string() + "'",
                   dir)
            .status == 0);
}

TEST_CASE("target compare prints a profile raised by 1.5 mm as a 1.5 mm level offset with no tilt or shape") {
  const fs::path dir = scratch("compare");
  std::ofstream measured(dir / "measured.csv"), simulated(dir / "simulated.csv");
  measured << "# a photo's profile\nx_mm,z_mm\n";
  simulated << "x_mm,z_mm\n";
  for (int k = 0; k <= 40; ++k) {
    const double x_mm = -20.0 + k;  // simulated: -20..20 mm; measured only -20..10 mm
    const double z_mm = 1e3 * kSurface(1e-3 * x_mm);
    if (x_mm <= 10.0) measured << x_mm << ',' << z_mm << '\n';
    simulated << x_mm << ',' << z_mm + 1.5 << '\n';
  }
  measured.close();
  simulated.close();
  const CliRun run = run_demfit(
      "target compare '" + (dir / "simulated.csv").string() + "' '" + (dir / "measured.csv").string() + "'", dir);
  INFO("stdout: " << run.output << "stderr: " << run.error);
  REQUIRE(run.status == 0);
  CHECK(run.output.find("common x-range -20.00 .. 10.00 mm") != std::string::npos);
  CHECK(run.output.find("RMS gap 1.500 mm, differing area 45.0 mm2") != std::string::npos);
  CHECK(run.output.find("level offset +1.500 mm") != std::string::npos);
  // The angle difference is 0 up to round-off (printed +0.00 or -0.00).
  CHECK(run.output.find("0.00 deg, tilt 0.000 mm RMS, shape 0.000 mm RMS") != std::string::npos);
}

TEST_CASE("target compare refuses a profile whose x does not increase naming the file and row") {
  const fs::path dir = scratch("compare_unsorted");
  std::ofstream(dir / "a.csv") << "x_mm,z_mm\n0,1\n2,1\n1,1\n";
  std::ofstream(dir / "b.csv") << "x_mm,z_mm\n0,1\n2,1\n";
  const CliRun run =
      run_demfit("target compare '" + (dir / "a.csv").string() + "' '" + (dir / "b.csv").string() + "'", dir);
  CHECK(run.status != 0);
  CHECK(run.error.find("a.csv") != std::string::npos);
  CHECK(run.error.find("row 3") != std::string::npos);
  CHECK(std::count(run.error.begin(), run.error.end(), '\n') == 1);
}
