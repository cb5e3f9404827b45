#pragma once
// Internal: running gnuplot as a separate process (never linked). Plots are PNG through the
// pngcairo terminal when gnuplot has it, else the plain png terminal.
#include <filesystem>
#include <string>

namespace demfit::identify::detail {

bool gnuplot_available();
// Runs `commands` (which must plot to the file named by the gnuplot variable `out`) and renames
// the PNG into place. Returns an empty string on success, else the reason.
std::string gnuplot_png(const std::filesystem::path& png, const std::string& commands);
// Quotes a path or label for a gnuplot string literal.
std::string gnuplot_quote(const std::string& text);

}  // namespace demfit::identify::detail
