#pragma once
// Running gnuplot as a separate process (never linked, never through a shell). Plots are PNG
// through the pngcairo terminal when gnuplot has it, else the plain png terminal. Shared by the
// study report (identify) and the diagnosis report (diagnose).
#include <filesystem>
#include <string>

namespace demfit::identify {

bool gnuplot_available();
// Runs `commands` in the folder of `png` (data files are named relative to it; plot to the
// gnuplot variable `out`) and renames the PNG into place. The script and the image are written
// under fixed names derived from the PNG's own (a safe slug); the script is removed afterwards.
// The image is 900 pixels wide and `height` high. Returns "" on success, else the reason.
std::string gnuplot_png(const std::filesystem::path& png, const std::string& commands, int height = 600);
// Quotes a file name or label for a gnuplot string literal; control characters (which would end
// the gnuplot command and start a new one) become '?'.
std::string gnuplot_quote(const std::string& text);

}  // namespace demfit::identify
