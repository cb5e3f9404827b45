// The self-contained HTML report writer (see report_html.hpp).
#include "demfit/identify/report_html.hpp"

#include <algorithm>
#include <cstdint>
#include <exception>

#include "demfit/identify/safe_output.hpp"

namespace demfit::identify {
namespace {

// The page's style: readable tables, pictures scaled to the page width, warnings that stand out.
constexpr const char* kStyle =
    "body{font-family:sans-serif;margin:1.5em auto;max-width:1100px;padding:0 1em;color:#222;line-height:1.4}"
    "h1{font-size:1.6em;border-bottom:2px solid #444}h2{font-size:1.3em;margin-top:1.6em;"
    "border-bottom:1px solid #aaa}h3,h4{font-size:1.1em}"
    "table{border-collapse:collapse;margin:.6em 0;font-size:.9em}th,td{border:1px solid #bbb;padding:.2em .5em;"
    "text-align:left;vertical-align:top}th{background:#eee}"
    "code{background:#f3f3f3;padding:0 .2em;word-break:break-all}"
    ".warning{background:#fff3cd;border-left:5px solid #d9a400;padding:.4em .8em;margin:.4em 0}"
    ".note{color:#666;font-style:italic}"
    "figure{margin:1em 0}figure img{max-width:100%;height:auto;border:1px solid #ccc}"
    "figcaption{font-size:.9em;color:#444}";

// No network and no script: only embedded pictures and the inline style sheet may load.
constexpr const char* kContentPolicy = "default-src 'none'; img-src data:; style-src 'unsafe-inline'";

bool is_png(const std::string& bytes) { return bytes.rfind("\x89PNG\r\n\x1a\n", 0) == 0; }

std::string trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return "";
  const auto last = text.find_last_not_of(" \t\r");
  return std::string(text.substr(first, last - first + 1));
}

// `code` spans and **bold** in escaped text; a marker without its partner stays as written.
std::string inline_markdown(std::string_view text) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == '`') {
      const auto end = text.find('`', i + 1);
      if (end != std::string_view::npos) {
        out += "<code>" + html_escape(text.substr(i + 1, end - i - 1)) + "</code>";
        i = end + 1;
        continue;
      }
    }
    if (text.compare(i, 2, "**") == 0) {
      const auto end = text.find("**", i + 2);
      if (end != std::string_view::npos) {
        out += "<strong>" + inline_markdown(text.substr(i + 2, end - i - 2)) + "</strong>";
        i = end + 2;
        continue;
      }
    }
    out += html_escape(text.substr(i, 1));
    ++i;
  }
  return out;
}

// The cells of a pipe-table row "| a | b |".
std::vector<std::string> table_cells(const std::string& row) {
  std::string inner = trim(row);
  if (!inner.empty() && inner.front() == '|') inner.erase(0, 1);
  if (!inner.empty() && inner.back() == '|') inner.pop_back();
  std::vector<std::string> cells;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= inner.size(); ++i)
    if (i == inner.size() || inner[i] == '|') {
      cells.push_back(trim(std::string_view(inner).substr(start, i - start)));
      start = i + 1;
    }
  return cells;
}

bool separator_row(const std::vector<std::string>& cells) {
  return std::all_of(cells.begin(), cells.end(), [](const std::string& c) {
    return !c.empty() && c.find_first_not_of(":-") == std::string::npos && c.find('-') != std::string::npos;
  });
}

// "![alt](file)" alone on a line: the file name, else "".
std::string picture_line(const std::string& line, std::string& alt) {
  if (line.rfind("![", 0) != 0 || line.back() != ')') return "";
  const auto middle = line.find("](");
  if (middle == std::string::npos) return "";
  alt = line.substr(2, middle - 2);
  return line.substr(middle + 2, line.size() - middle - 3);
}

// Appends <hN>html</hN> (N clamped to 1..4); `html` is already escaped.
void element(std::string& body, int level, const std::string& html) {
  const char digit = static_cast<char>('0' + std::clamp(level, 1, 4));
  body.append("<h").append(1, digit).append(">").append(html).append("</h").append(1, digit).append(">\n");
}

}  // namespace

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string base64_encode(std::string_view bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    // Three bytes (zero-filled past the end) make four 6-bit digits; '=' stands for missing bytes.
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t group = 0;
    for (std::size_t k = 0; k < 3; ++k)
      group = (group << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k)
      out += k <= n ? kAlphabet[(group >> (18 - 6 * k)) & 0x3f] : '=';
  }
  return out;
}

HtmlReport::HtmlReport(std::string title, std::filesystem::path folder)
    : title_(std::move(title)), folder_(std::move(folder)) {}

void HtmlReport::heading(int level, const std::string& text) {
  element(body_, level, html_escape(text));
}

void HtmlReport::paragraph(const std::string& text) { body_ += "<p>" + html_escape(text) + "</p>\n"; }

void HtmlReport::warning(const std::string& text) {
  body_ += "<p class=\"warning\"><strong>warning:</strong> " + html_escape(text) + "</p>\n";
}

void HtmlReport::list(const std::vector<std::string>& items) {
  body_ += "<ul>\n";
  for (const auto& item : items) body_ += "<li>" + html_escape(item) + "</li>\n";
  body_ += "</ul>\n";
}

void HtmlReport::table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  body_ += "<table>\n<tr>";
  for (const auto& h : header) body_ += "<th>" + html_escape(h) + "</th>";
  body_ += "</tr>\n";
  for (const auto& row : rows) {
    body_ += "<tr>";
    for (const auto& cell : row) body_ += "<td>" + html_escape(cell) + "</td>";
    body_ += "</tr>\n";
  }
  body_ += "</table>\n";
}

bool HtmlReport::picture(const std::string& file_name, const std::string& caption,
                         const std::filesystem::path& folder) {
  std::string bytes;
  try {
    bytes = read_input_file(path_inside(folder.empty() ? folder_ : folder, file_name), kMaxEmbeddedPictureBytes, "picture");
  } catch (const std::exception&) {
    bytes.clear();
  }
  if (!is_png(bytes)) {
    body_ += "<p class=\"note\">picture " + html_escape(printable(file_name)) + " not available</p>\n";
    return false;
  }
  body_ += "<figure><img alt=\"" + html_escape(caption) + "\" src=\"data:image/png;base64," + base64_encode(bytes) +
           "\"><figcaption>" + html_escape(caption) + "</figcaption></figure>\n";
  pictures_.push_back(file_name);
  return true;
}

void HtmlReport::markdown(const std::string& text, bool pictures) {
  std::vector<std::string> paragraph, rows;
  int list_depth = 0;  // open <ul> elements
  auto flush = [&] {
    if (!paragraph.empty()) {
      std::string joined;
      for (const auto& line : paragraph) joined += (joined.empty() ? "" : " ") + line;
      body_ += "<p>" + inline_markdown(joined) + "</p>\n";
      paragraph.clear();
    }
    for (; list_depth > 0; --list_depth) body_ += "</li></ul>\n";
    if (!rows.empty()) {
      const bool header = rows.size() >= 2 && separator_row(table_cells(rows[1]));
      body_ += "<table>\n";
      for (std::size_t r = 0; r < rows.size(); ++r) {
        if (header && r == 1) continue;
        const char* tag = header && r == 0 ? "th" : "td";
        body_ += "<tr>";
        for (const auto& cell : table_cells(rows[r]))
          body_ += std::string("<") + tag + ">" + inline_markdown(cell) + "</" + tag + ">";
        body_ += "</tr>\n";
      }
      body_ += "</table>\n";
      rows.clear();
    }
  };
  std::size_t start = 0;
  while (start <= text.size()) {
    const auto end = std::min(text.find('\n', start), text.size());
    const std::string raw = text.substr(start, end - start);
    start = end + 1;
    const std::string line = trim(raw);
    std::string alt;
    if (line.empty()) {
      flush();
    } else if (line.front() == '#') {
      flush();
      const auto level = line.find_first_not_of('#');
      if (level == std::string::npos) continue;
      element(body_, std::max(2, static_cast<int>(level) + 1), inline_markdown(trim(std::string_view(line).substr(level))));
    } else if (line.front() == '|') {
      if (!paragraph.empty() || list_depth > 0) flush();
      rows.push_back(line);
    } else if (line.rfind("- ", 0) == 0) {
      if (!paragraph.empty() || !rows.empty()) flush();
      // Two spaces of indentation per nesting level.
      const int depth = 1 + static_cast<int>(raw.find_first_not_of(' ') / 2);
      if (depth > list_depth) {
        for (; list_depth < depth; ++list_depth) body_ += "<ul><li>";
      } else {
        for (; list_depth > depth; --list_depth) body_ += "</li></ul>\n";
        body_ += "</li>\n<li>";
      }
      body_ += inline_markdown(line.substr(2));
    } else if (const std::string file = picture_line(line, alt); !file.empty()) {
      flush();
      if (pictures)
        picture(file, alt);
      else
        body_ += "<p class=\"note\">" + html_escape(printable(file)) + ": shown above</p>\n";
    } else {
      if (!rows.empty() || list_depth > 0) flush();
      paragraph.push_back(line);
    }
  }
  flush();
}

std::string HtmlReport::page() const {
  return std::string("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n") +
         "<meta http-equiv=\"Content-Security-Policy\" content=\"" + kContentPolicy + "\">\n" +
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" + html_escape(title_) +
         "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n<h1>" + html_escape(title_) + "</h1>\n" + body_ +
         "</body>\n</html>\n";
}

void write_html_report(const std::filesystem::path& folder, const std::string& file_name, const HtmlReport& report) {
  write_file_atomically(path_inside(folder, file_name), report.page());
}

}  // namespace demfit::identify
