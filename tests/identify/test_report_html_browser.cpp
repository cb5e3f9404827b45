// report.html in a real browser: headless Chromium (a test dependency, scripts/setup) loads the
// page of a small study, and its screenshot is decoded to check that the plots are drawn.
// Two Chromium starts in all: one --dump-dom of a copy of the page with a checking script added,
// one --screenshot of the page itself.
#include <catch2/catch.hpp>

#include <chrono>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <signal.h>
#include <sstream>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/gnuplot.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/imaging/image.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;
namespace fs = std::filesystem;

namespace {

constexpr const char* kChromium = "/usr/bin/chromium";
constexpr int kWidth = 1200, kHeight = 3000;  // [px] the browser window, the same for both starts

std::string read_all(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs argv (argv[0] an absolute path) with stdout and stderr into files, in its own process group,
// killed with that group after `seconds`. Returns the exit status, -1 on the time limit.
int run_limited(const std::vector<std::string>& argv, const fs::path& out, const fs::path& err, int seconds) {
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    setpgid(0, 0);
    const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (o < 0 || e < 0 || dup2(o, 1) < 0 || dup2(e, 2) < 0) _exit(126);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  setpgid(pid, pid);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      kill(-pid, SIGKILL);
      waitpid(pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::vector<std::string> chromium(const fs::path& profile, const std::vector<std::string>& extra) {
  std::vector<std::string> argv = {kChromium, "--headless", "--no-sandbox", "--disable-gpu",
                                   "--user-data-dir=" + profile.string(), "--hide-scrollbars",
                                   "--window-size=" + std::to_string(kWidth) + "," + std::to_string(kHeight)};
  argv.insert(argv.end(), extra.begin(), extra.end());
  return argv;
}

// Added to the copy of the page: after load, writes the page's errors (script errors, failed
// loads, console.error calls) and, per image, its natural size and place in the window into the DOM.
constexpr const char* kCheckScript = R"(<script>
var demfitErrors = [];
window.addEventListener('error', function (e) { demfitErrors.push('error ' + (e.message || (e.target && e.target.tagName))); }, true);
var demfitConsoleError = console.error;
console.error = function () { demfitErrors.push('console ' + Array.prototype.join.call(arguments, ' ')); demfitConsoleError.apply(console, arguments); };
window.addEventListener('load', function () {
  var lines = ['errors ' + demfitErrors.length].concat(demfitErrors);
  for (var i = 0; i < document.images.length; ++i) {
    var img = document.images[i], r = img.getBoundingClientRect();
    lines.push('image ' + img.naturalWidth + ' ' + img.naturalHeight + ' ' + Math.round(r.left) + ' ' +
               Math.round(r.top) + ' ' + Math.round(r.width) + ' ' + Math.round(r.height));
  }
  var pre = document.createElement('pre');
  pre.id = 'demfit-check';
  pre.textContent = lines.join('\n');
  document.body.appendChild(pre);
});
</script>
)";

struct ImageBox {
  int natural_width = 0, natural_height = 0, left = 0, top = 0, width = 0, height = 0;
};

// Share of the pixels inside `box` (clipped to the screenshot) that are not the white background.
double drawn_share(const demfit::imaging::GreyImage& shot, const ImageBox& box) {
  long drawn = 0, total = 0;
  for (int row = std::max(0, box.top); row < std::min(shot.height, box.top + box.height); ++row)
    for (int col = std::max(0, box.left); col < std::min(shot.width, box.left + box.width); ++col) {
      ++total;
      drawn += shot.value[static_cast<std::size_t>(row) * shot.width + col] < 0.9f ? 1 : 0;
    }
  return total ? static_cast<double>(drawn) / static_cast<double>(total) : 0.0;
}

}  // namespace

TEST_CASE("report.html of a study loads in headless Chromium without an error and its plots are drawn",
          "[identify][html][browser]") {
  REQUIRE(fs::exists(kChromium));
  REQUIRE(gnuplot_available());  // both are test dependencies (scripts/setup)
  const auto dir = test::fresh_dir("html_browser");
  const auto study_dir = dir / "study";
  RunOptions options = test::quiet_options(study_dir);
  options.plots = true;
  run_study(parse_study(test::analytic_study(0.01, 5), "."), AnalyticCurveModel(), options);
  const std::string page = read_all(study_dir / "report.html");
  REQUIRE(page.find("</body>") != std::string::npos);

  // (i) A copy with the checking script; its policy also lets that one inline script run.
  std::string checked = page;
  const std::string policy = "default-src 'none';";
  REQUIRE(checked.find(policy) != std::string::npos);
  checked.replace(checked.find(policy), policy.size(), policy + " script-src 'unsafe-inline';");
  checked.insert(checked.rfind("</body>"), kCheckScript);
  std::ofstream(dir / "checked.html") << checked;
  const int dump = run_limited(chromium(dir / "profile", {"--enable-logging=stderr", "--v=0",
                                                          "--virtual-time-budget=5000", "--dump-dom",
                                                          "file://" + fs::absolute(dir / "checked.html").string()}),
                               dir / "dom.html", dir / "dom.log", 60);
  REQUIRE(dump == 0);
  // No console message at all: the page has no script, so any is an error or a blocked load.
  std::istringstream log(read_all(dir / "dom.log"));
  for (std::string line; std::getline(log, line);) {
    INFO(line);
    CHECK(line.find(":CONSOLE") == std::string::npos);
  }
  const std::string dom = read_all(dir / "dom.html");
  const auto start = dom.find("<pre id=\"demfit-check\">");
  REQUIRE(start != std::string::npos);
  std::istringstream report(dom.substr(start + 23, dom.find("</pre>", start) - start - 23));
  std::string word;
  int errors = -1;
  report >> word >> errors;
  CHECK(word == "errors");
  CHECK(errors == 0);
  std::vector<ImageBox> boxes;
  while (report >> word) {
    if (word != "image") continue;
    ImageBox b;
    report >> b.natural_width >> b.natural_height >> b.left >> b.top >> b.width >> b.height;
    boxes.push_back(b);
  }
  // The target fit, the objective history, one plot per variable and the posterior pairs.
  REQUIRE(boxes.size() == 5);
  for (const auto& b : boxes) {
    CHECK(b.natural_width > 0);
    CHECK(b.natural_height > 0);
    CHECK(b.width > 100);
  }

  // (ii) The page itself on screen: inside each picture visible in the window, plot lines,
  // points and labels cover a share of the pixels that a blank or broken image would not.
  const int shot = run_limited(chromium(dir / "profile", {"--screenshot=" + (dir / "shot.png").string(),
                                                          "file://" + fs::absolute(study_dir / "report.html").string()}),
                               dir / "shot.out", dir / "shot.log", 60);
  REQUIRE(shot == 0);
  fs::remove_all(dir / "profile");  // the browser's own cache and settings, several MB
  const auto screenshot = demfit::imaging::read_grey_image(dir / "shot.png");
  REQUIRE(screenshot.width == kWidth);
  int visible = 0;
  for (const auto& b : boxes) {
    if (b.top + b.height > screenshot.height) continue;
    ++visible;
    const double share = drawn_share(screenshot, b);
    INFO("picture at " << b.left << "," << b.top << ": " << share << " of its pixels drawn");
    CHECK(share > 0.02);
  }
  CHECK(visible >= 2);
}
