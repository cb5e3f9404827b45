#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <regex>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/gnuplot.hpp"
#include "demfit/identify/report_html.hpp"
#include "demfit/identify/reported_interval.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_store.hpp"
#include "demfit/identify/study_warnings.hpp"
#include "demfit/imaging/image.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

std::string read_all(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// An independent base64 decoder (RFC 4648 section 4), for reading the embedded pictures back.
std::string base64_decode(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::uint32_t bits = 0;
  int count = 0;
  for (const char c : text) {
    if (c == '=') break;
    const auto digit = alphabet.find(c);
    if (digit == std::string::npos) FAIL("not a base64 digit: " << c);
    bits = (bits << 6) | static_cast<std::uint32_t>(digit);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out += static_cast<char>((bits >> count) & 0xff);
    }
  }
  return out;
}

// The decoded bytes of every data: URI picture of a page, in order.
std::vector<std::string> embedded_pictures(const std::string& page) {
  // (std::regex recurses per character: a picture of a few hundred kB would overflow the stack.)
  std::vector<std::string> pictures;
  const std::string prefix = "src=\"data:image/png;base64,";
  for (auto start = page.find(prefix); start != std::string::npos; start = page.find(prefix, start)) {
    start += prefix.size();
    const auto end = page.find('"', start);
    REQUIRE(end != std::string::npos);
    pictures.push_back(base64_decode(page.substr(start, end - start)));
  }
  return pictures;
}

// A small PNG with a colour gradient (every byte value of the image data occurs).
std::string gradient_png(int width, int height) {
  demfit::imaging::RgbImage image{width, height, {}};
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col)
      for (int c = 0; c < 3; ++c) image.rgb.push_back(static_cast<std::uint8_t>((row * 7 + col * 13 + c * 101) % 256));
  return demfit::imaging::encode_png(image);
}

// A value as the report's tables print it ("%.6g").
std::string six_digits(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("html_escape writes the five HTML special characters as character references", "[identify][html]") {
  CHECK(html_escape("a&b<c>d\"e'f") == "a&amp;b&lt;c&gt;d&quot;e&#39;f");
  CHECK(html_escape("plain text, 1.5 mm") == "plain text, 1.5 mm");
}

TEST_CASE("A name containing <script> shows as text everywhere in the page, never as markup", "[identify][html]") {
  const std::string hostile = "<script>alert('x')</script>\"><img src=x onerror=alert(1)>";
  HtmlReport html("study " + hostile, test::fresh_dir("html_escape"));
  html.heading(2, hostile);
  html.paragraph(hostile);
  html.warning(hostile);
  html.list({hostile});
  html.table({hostile}, {{hostile}});
  html.picture(hostile, hostile);
  html.markdown("# " + hostile + "\n\n| " + hostile + " |\n|---|\n| `" + hostile + "` |\n\n- **" + hostile + "**\n\n" +
                    hostile + "\n![" + hostile + "](" + hostile + ")\n",
                true);
  const std::string page = html.page();
  std::string lower = page;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  CHECK_FALSE(contains(lower, "<script"));
  CHECK_FALSE(contains(lower, "<img src=x"));
  // "onerror=" occurs only as escaped text, never as an attribute of an element.
  CHECK_FALSE(std::regex_search(page, std::regex(R"(<[a-z][^<>]*\son[a-z]+\s*=)", std::regex::icase)));
  CHECK(contains(page, "&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;&quot;&gt;&lt;img src=x onerror=alert(1)&gt;"));
}

TEST_CASE("base64_encode gives the RFC 4648 test vectors", "[identify][html]") {
  CHECK(base64_encode("") == "");
  CHECK(base64_encode("f") == "Zg==");
  CHECK(base64_encode("fo") == "Zm8=");
  CHECK(base64_encode("foo") == "Zm9v");
  CHECK(base64_encode("foob") == "Zm9vYg==");
  CHECK(base64_encode("fooba") == "Zm9vYmE=");
  CHECK(base64_encode("foobar") == "Zm9vYmFy");
  std::string all_bytes;
  for (int b = 0; b < 256; ++b) all_bytes += static_cast<char>(b);
  CHECK(base64_decode(base64_encode(all_bytes)) == all_bytes);
}

TEST_CASE("An embedded picture decodes back to the bytes of its PNG file", "[identify][html]") {
  const auto dir = test::fresh_dir("html_picture");
  const std::string first = gradient_png(31, 17), second = gradient_png(64, 48);
  write_file_atomically(dir / "a.png", first);
  write_file_atomically(dir / "b.png", second);
  HtmlReport html("pictures", dir);
  CHECK(html.picture("a.png", "first"));
  html.markdown("text\n\n![second](b.png)\n", true);
  const auto pictures = embedded_pictures(html.page());
  REQUIRE(pictures.size() == 2);
  CHECK(pictures[0] == first);
  CHECK(pictures[1] == second);
  CHECK(html.pictures() == std::vector<std::string>{"a.png", "b.png"});
}

TEST_CASE("A missing picture, a file that is not a PNG or a name leaving the folder leaves a note, no image",
          "[identify][html]") {
  const auto dir = test::fresh_dir("html_missing_picture");
  write_file_atomically(dir / "text.png", "not a picture");
  HtmlReport html("pictures", dir);
  CHECK_FALSE(html.picture("absent.png", "absent"));
  CHECK_FALSE(html.picture("text.png", "text"));
  CHECK_FALSE(html.picture("../outside.png", "outside"));
  html.markdown("![remote](http://example.com/a.png)\n", true);
  const std::string page = html.page();
  CHECK_FALSE(contains(page, "<img"));
  CHECK(contains(page, "picture absent.png not available"));
  CHECK(contains(page, "picture text.png not available"));
  CHECK(contains(page, "picture ../outside.png not available"));
}

TEST_CASE("The page fetches nothing: no http or https source or link, and its policy forbids any fetch",
          "[identify][html]") {
  HtmlReport html("links", test::fresh_dir("html_links"));
  html.markdown("[a link](https://example.com) and ![remote](https://example.com/a.png)\n", true);
  const std::string page = html.page();
  CHECK_FALSE(std::regex_search(page, std::regex(R"((src|href)\s*=\s*["']?\s*https?:)", std::regex::icase)));
  CHECK_FALSE(std::regex_search(page, std::regex(R"(<(script|link|iframe|object|embed)\b)", std::regex::icase)));
  CHECK(contains(page, "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; "
                       "style-src 'unsafe-inline'\">"));
}

TEST_CASE("The Markdown of a report renders as headings, tables with a header row, nested lists and paragraphs",
          "[identify][html]") {
  HtmlReport html("markdown", test::fresh_dir("html_markdown"));
  html.markdown("# Title\n\n- model: `drum`\n  - inner **bold**\n- second\n\n| a | b |\n|---|---|\n| 1 | 2 |\n\n"
                "one line\nsame paragraph\n",
                false);
  const std::string page = html.page();
  CHECK(contains(page, "<h2>Title</h2>"));
  CHECK(contains(page, "<ul><li>model: <code>drum</code><ul><li>inner <strong>bold</strong></li></ul>\n</li>\n"
                       "<li>second</li></ul>"));
  CHECK(contains(page, "<table>\n<tr><th>a</th><th>b</th></tr>\n<tr><td>1</td><td>2</td></tr>\n</table>"));
  CHECK(contains(page, "<p>one line same paragraph</p>"));
}

TEST_CASE("report.html of a study shows the answer's values and intervals, the warnings, then fits, convergence and "
          "posterior, its plots embedded",
          "[identify][html][report]") {
  const auto dir = test::fresh_dir("html_study");
  // Five iterations: the study stops at the iteration limit, which it warns about.
  const auto spec = parse_study(test::analytic_study(0.01, 5), ".");
  RunOptions options = test::quiet_options(dir);
  options.plots = true;
  const StudyResult result = run_study(spec, AnalyticCurveModel(), options);
  const std::string page = read_all(dir / "report.html");
  REQUIRE_FALSE(page.empty());
  std::size_t position = page.find("<h2>Answer</h2>");
  REQUIRE(position != std::string::npos);
  for (const char* name : {"amplitude", "rate"}) {
    INFO(name);
    const ReportedInterval& interval = result.intervals.at(name);
    REQUIRE(interval.available);
    const auto row = page.find("<td>" + std::string(name) + "</td><td>" + six_digits(result.best.at(name)) +
                                   "</td><td>" + html_escape(interval_text(interval)) + "</td>",
                               position);
    REQUIRE(row != std::string::npos);
    position = row;
  }
  const auto warnings = study_diagnostics(StudyStore::open_existing(dir / "study.db")).warnings;
  REQUIRE_FALSE(warnings.empty());
  for (const auto& w : warnings) {
    const auto found = page.find("<strong>warning:</strong> " + html_escape(w), position);
    REQUIRE(found != std::string::npos);
    position = found;
  }
  if (!gnuplot_available()) return;  // without gnuplot the study draws no plots (report.md says so)
  for (const char* section : {"<h2>Fits: measured vs simulated</h2>", "<h2>Convergence</h2>", "<h2>Posterior</h2>",
                              "<h2>Full report</h2>"}) {
    INFO(section);
    const auto found = page.find(section, position);
    REQUIRE(found != std::string::npos);
    position = found;
  }
  // Each picture is the PNG on disk, in the order of the sections.
  const auto pictures = embedded_pictures(page);
  const std::vector<std::string> files = {"target_response.png", "objective_history.png", "variable_amplitude.png",
                                          "variable_rate.png", "posterior_pairs.png"};
  REQUIRE(pictures.size() == files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    INFO(files[i]);
    CHECK(pictures[i] == read_all(dir / files[i]));
  }
}
