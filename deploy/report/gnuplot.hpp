#pragma once
// Plots of the result tables: a gnuplot script written next to its PNG (so that it can be
// redrawn by hand) and run in the output folder. Columns are named by their CSV header.
#include <string>
#include <vector>

namespace maptr::deploy::report {

/// The page of a plot: PNG size in pixels and an optional font (e.g. ",11").
struct PlotFrame {
  std::string size = "900,600";
  std::string font;
};

/// One curve: `file` (relative to the output folder) using columns x and y by name.
struct Curve {
  std::string file, x, y, style = "lines lw 2", title, axes;
};

/// `plot` over several curves, one per line (an empty file name repeats the previous one).
std::string plot_command(const std::vector<Curve>& curves);

/// The whole script: a comment, the PNG terminal, output STEM.png, comma-separated data, body.
std::string plot_script(const std::string& stem, const std::string& comment, const PlotFrame& frame,
                        const std::string& body);

/// Writes DIR/STEM.gp and runs gnuplot in DIR; false (with a message on stderr) when gnuplot
/// fails, whose output is then kept in DIR/STEM.gnuplot.log.
bool draw_plot(const std::string& dir, const std::string& stem, const std::string& comment,
               const PlotFrame& frame, const std::string& body);

}  // namespace maptr::deploy::report
