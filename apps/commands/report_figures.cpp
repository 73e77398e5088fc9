// The report's figures (report_figures.hpp).
#include "report_figures.hpp"

#include <fmt/format.h>

#include "python_plot.hpp"

namespace craterkit::cli {

const std::vector<std::string>& report_figure_files() {
  static const std::vector<std::string> files{"scaled_radius.png", "sci_cohesion.png", "friction.png",
                                              "rates.png", "ages.png"};
  return files;
}

DrawnFigures draw_report_figures(const std::filesystem::path& report_json, const std::filesystem::path& dir,
                                 const std::vector<Figure>& figures) {
  DrawnFigures out;
  // A figure of an earlier report in the same folder must not pass for one of this report.
  for (const auto& name : report_figure_files()) {
    std::error_code ignored;
    std::filesystem::remove(dir / name, ignored);
  }
  if (figures.empty()) return out;
  constexpr const char* kOverride = "CRATERKIT_PLOT_REPORT_SCRIPT";
  const auto script = plot_script("plot_report.py", kOverride);
  out.why = plotting_unavailable(script, kOverride);
  int status = 0;
  if (out.why.empty()) {
    std::vector<std::string> args{script.string(), report_json.string(), dir.string()};
    for (const auto& figure : figures) args.push_back(figure.file);
    status = run_python(args);
  }
  for (const auto& figure : figures) {
    std::error_code ignored;
    (std::filesystem::exists(dir / figure.file, ignored) ? out.drawn : out.skipped).push_back(figure);
  }
  if (out.why.empty() && !out.skipped.empty())
    out.why = fmt::format("plot_report.py failed (exit status {}; its message is above)", status);
  return out;
}

std::string figures_markdown(const DrawnFigures& figures) {
  std::string md;
  if (figures.drawn.empty() && figures.skipped.empty()) return md;
  md += "\n## Figures\n";
  for (const auto& f : figures.drawn)
    md += fmt::format("\n![{}]({})\n\n{}: {}.\n", f.file, f.file, f.file, f.caption);
  if (!figures.skipped.empty()) {
    std::string names;
    for (const auto& f : figures.skipped) names += (names.empty() ? "" : ", ") + f.file;
    md += fmt::format("\nFigures skipped ({}): {}. The numbers above do not depend on them.\n", names,
                      figures.why);
  }
  return md;
}

}  // namespace craterkit::cli
