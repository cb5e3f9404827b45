#pragma once
// A self-contained HTML report (report.html beside report.md): one file that opens in any browser
// without network access. Every picture is embedded as a base64 data: URI (RFC 2045 alphabet,
// RFC 2397 URI), the style sheet is inline, the page holds no script, and its Content Security
// Policy (default-src 'none'; img-src data:) forbids the browser to fetch anything at all.
//
// Every text given to the writer is plain text: it is HTML-escaped (& < > " '), so a name such as
// "<script>" shows as written and never becomes markup. Headings, tables, lists and pictures come
// from the writer's own calls; `markdown` renders the subset of Markdown that demfit's report.md
// files use (headings, pipe tables, bullet lists, paragraphs, **bold**, `code`, ![alt](picture)).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace demfit::identify {

// Text with & < > " ' written as character references: safe as element content and inside a
// double- or single-quoted attribute value.
std::string html_escape(std::string_view text);

// Standard base64 (A-Z a-z 0-9 + /, '=' padding, no line breaks).
std::string base64_encode(std::string_view bytes);

// Largest picture embedded (a larger file is named in the page instead).
inline constexpr std::size_t kMaxEmbeddedPictureBytes = 32u << 20;

class HtmlReport {
 public:
  // `folder`: the output folder the pictures are read from (picture names are plain file names in it).
  HtmlReport(std::string title, std::filesystem::path folder);

  void heading(int level, const std::string& text);  // level 1..4
  void paragraph(const std::string& text);
  void warning(const std::string& text);  // a highlighted line
  void list(const std::vector<std::string>& items);
  void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
  // Embeds the PNG `file_name` of the report's folder (or of `folder` when given) with a caption. A
  // missing, oversized or non-PNG file leaves a note naming it instead; returns whether it was embedded.
  bool picture(const std::string& file_name, const std::string& caption, const std::filesystem::path& folder = {});
  // Renders Markdown text (the subset above). Picture lines are embedded when `pictures`, else
  // named as shown above (the page shows them in sections of their own).
  void markdown(const std::string& text, bool pictures);

  // The whole page.
  std::string page() const;
  // Names of the pictures embedded so far (in order).
  const std::vector<std::string>& pictures() const { return pictures_; }

 private:
  std::string title_;
  std::filesystem::path folder_;
  std::string body_;
  std::vector<std::string> pictures_;
};

// Writes report.page() to folder/file_name atomically (write_file_atomically; the name must be a
// plain file name inside the folder).
void write_html_report(const std::filesystem::path& folder, const std::string& file_name, const HtmlReport& report);

}  // namespace demfit::identify
