#include "demfit/identify/gnuplot.hpp"

#include <unistd.h>

#include "demfit/identify/run_program.hpp"
#include "demfit/identify/safe_output.hpp"

namespace demfit::identify {

bool gnuplot_available() { return program_available("gnuplot"); }

std::string gnuplot_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f)
      out += '?';
    else
      out += (c == '\'') ? std::string("''") : std::string(1, c);
  }
  return out + "'";
}

std::string gnuplot_png(const std::filesystem::path& png, const std::string& commands, int height) {
  const std::filesystem::path folder = png.has_parent_path() ? png.parent_path() : std::filesystem::path(".");
  const std::string name = safe_slug(png.filename().string());
  const std::string suffix = ".tmp" + std::to_string(::getpid());
  const std::string temporary_png = name + suffix;
  const std::string script = name + ".gp" + suffix;
  try {
    write_file_atomically(path_inside(folder, script),
                          "out = " + gnuplot_quote(temporary_png) + "\n" +
                              "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 900," +
                              std::to_string(height) + " noenhanced } else { set terminal png size 900," +
                              std::to_string(height) +
                              " noenhanced }\n"
                              "set output out\nset grid\nset key below\n" +
                              commands + "\nunset output\n");
  } catch (const std::exception& e) { return e.what(); }
  const int status = run_program({"gnuplot", script}, folder);
  std::error_code ignored;
  std::filesystem::remove(folder / script, ignored);
  if (status != 0 || !std::filesystem::exists(folder / temporary_png)) {
    std::filesystem::remove(folder / temporary_png, ignored);
    return "gnuplot failed for " + name;
  }
  std::filesystem::rename(folder / temporary_png, folder / name, ignored);
  if (ignored) return "cannot move " + name + " into place: " + ignored.message();
  return {};
}

}  // namespace demfit::identify
