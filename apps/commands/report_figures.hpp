#pragma once
// The report's figures (report_builder.hpp), drawn from report.json by scripts/plot_report.py with
// /usr/bin/python3 and matplotlib. The numbers never depend on them: without Python or matplotlib the
// report says which figures were skipped and why.
#include <filesystem>
#include <string>
#include <vector>

namespace craterkit::cli {

struct Figure {
  std::string file;     // e.g. "rates.png", in the report's folder
  std::string caption;  // what it shows
};

// Every figure the report can have, in its order (for --overwrite and the stale ones of an earlier report).
const std::vector<std::string>& report_figure_files();

struct DrawnFigures {
  std::vector<Figure> drawn;
  std::vector<Figure> skipped;
  std::string why;  // why the skipped ones were not drawn
};

// Draws `figures` into `dir` from `report_json`. The script is scripts/plot_report.py beside the data
// (source tree) or inside it (installation), or CRATERKIT_PLOT_REPORT_SCRIPT.
DrawnFigures draw_report_figures(const std::filesystem::path& report_json, const std::filesystem::path& dir,
                                 const std::vector<Figure>& figures);

// The figures' section of report.md.
std::string figures_markdown(const DrawnFigures& figures);

}  // namespace craterkit::cli
