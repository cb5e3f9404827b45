#include "gnuplot.hpp"

#include <cstdlib>
#include <fstream>
#include <unistd.h>

namespace demfit::identify::detail {

bool gnuplot_available() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

std::string gnuplot_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += (c == '\'') ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string gnuplot_png(const std::filesystem::path& png, const std::string& commands) {
  const std::string suffix = ".tmp" + std::to_string(::getpid());
  std::filesystem::path temporary_png = png;
  temporary_png += suffix;
  std::filesystem::path script = png;
  script += ".gp" + suffix;
  {
    std::ofstream out(script);
    out << "out = " << gnuplot_quote(temporary_png.string()) << "\n"
        << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 900,600 noenhanced } "
           "else { set terminal png size 900,600 noenhanced }\n"
        << "set output out\nset grid\nset key below\n"
        << commands << "\nunset output\n";
  }
  const std::string command = "gnuplot " + gnuplot_quote(script.string()) + " >/dev/null 2>&1";
  const int status = std::system(command.c_str());
  std::filesystem::remove(script);
  if (status != 0 || !std::filesystem::exists(temporary_png)) {
    std::filesystem::remove(temporary_png);
    return "gnuplot failed for " + png.filename().string();
  }
  std::filesystem::rename(temporary_png, png);
  return {};
}

}  // namespace demfit::identify::detail
