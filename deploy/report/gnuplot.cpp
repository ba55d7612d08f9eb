#include "deploy/report/gnuplot.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace maptr::deploy::report {

std::string plot_command(const std::vector<Curve>& curves) {
  std::string p = "plot ";
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const Curve& c = curves[i];
    p += (i ? ", \\\n     " : "") + std::string("'") + c.file + "' using \"" + c.x + "\":\"" + c.y +
         "\" with " + c.style + (c.axes.empty() ? "" : " axes " + c.axes) + " title '" + c.title + "'";
  }
  return p + "\n";
}

std::string plot_script(const std::string& stem, const std::string& comment, const PlotFrame& frame,
                        const std::string& body) {
  return "# " + comment + "\n" + "set terminal pngcairo size " + frame.size +
         (frame.font.empty() ? "" : " font '" + frame.font + "'") + " noenhanced\n" + "set output '" + stem +
         ".png'\n" + "set datafile separator ','\n" + body;
}

bool draw_plot(const std::string& dir, const std::string& stem, const std::string& comment,
               const PlotFrame& frame, const std::string& body) {
  std::ofstream(dir + "/" + stem + ".gp") << plot_script(stem, comment, frame, body);
  const std::string cmd = "cd '" + dir + "' && gnuplot '" + stem + ".gp' > '" + stem + ".gnuplot.log' 2>&1";
  if (std::system(cmd.c_str()) != 0) {
    std::fprintf(
        stderr, "maptr: gnuplot failed for %s/%s.gp (see %s.gnuplot.log); the CSV and markdown are written\n",
        dir.c_str(), stem.c_str(), stem.c_str());
    return false;
  }
  std::error_code ec;
  std::filesystem::remove(dir + "/" + stem + ".gnuplot.log", ec);
  return true;
}

}  // namespace maptr::deploy::report
