// The report of radii tables (report_builder.hpp).
#include "report_builder.hpp"

#include <algorithm>
#include <cctype>
#include <iostream>
#include <set>

#include <fmt/format.h>

#include "craterkit/common/atomic_file.hpp"
#include "craterkit/scaling/grouped_fit.hpp"
#include "json_output.hpp"
#include "report_chronology.hpp"
#include "report_fits.hpp"
#include "report_sci.hpp"

namespace craterkit::cli {
namespace {

void say(bool progress, const std::string& text) {
  if (progress) std::cerr << "report: " << text << "\n";
}

// The fit file of each table: fit.json for one table, fit_<stem>.json for several (numbered when two
// stems are the same, e.g. two sweeps' radii.csv).
std::vector<std::string> fit_file_names(const std::vector<scaling::RadiiTable>& tables) {
  if (tables.size() == 1) return {"fit.json"};
  std::vector<std::string> names;
  std::set<std::string> taken;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    std::string stem = std::filesystem::path(tables[i].source).stem().string();
    for (auto& c : stem) {
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
    }
    std::string name = "fit_" + stem + ".json";
    for (int k = 2; taken.contains(name); ++k) name = fmt::format("fit_{}_{}.json", stem, k);
    taken.insert(name);
    names.push_back(name);
  }
  return names;
}

// A group's name in the report: its grouping values, after its table's name when there are several tables.
std::string law_label(const std::vector<TableFits>& fits, const TableFits& table_fits,
                      const scaling::GroupFit& group) {
  const std::string key = key_label(group.key);
  return fits.size() > 1 ? table_fits.table->source + ", " + key : key;
}

nlohmann::json fit_options_json(const ReportOptions& options) {
  const auto fit = report_fit_options();
  nlohmann::json fixed = nlohmann::json::object();
  for (const auto& [name, value] : fit.fixed) fixed[name] = value;
  return {{"form", scaling::to_string(fit.form)},
          {"fixed", fixed},
          {"weighted", false},
          {"starts", fit.starts},
          {"group_by", options.group_by ? nlohmann::json(*options.group_by) : nlohmann::json(nullptr)}};
}

}  // namespace

Report build_report(const std::vector<scaling::RadiiTable>& tables, const ReportOptions& options) {
  Report report;
  std::string& md = report.markdown;
  nlohmann::json& json = report.json;
  md = fmt::format("# {}\n\n{}. Input:", options.title, options.producer);
  nlohmann::json tables_json = nlohmann::json::array();
  for (const auto& table : tables) md += fmt::format(" {} ({} rows);", table.source, table.rows.size());
  md.back() = '.';
  md += "\n" + options.preamble;

  // 1. The fits.
  const auto names = fit_file_names(tables);
  std::vector<TableFits> fits;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    say(options.progress,
        fmt::format("fitting the scaling law to {} ({} rows)", tables[i].source, tables[i].rows.size()));
    fits.push_back(fit_table(tables[i], options.group_by, options.progress));
    auto& f = fits.back();
    if (f.result) {
      f.fit_file = names[i];
      report.fit_files.emplace_back(f.fit_file, f.fit_json);
    }
    tables_json.push_back(
        {{"source", tables[i].source},
         {"rows", tables[i].rows.size()},
         {"grouping_columns", tables[i].group_columns},
         {"fit_file", f.result ? nlohmann::json(f.fit_file) : nlohmann::json(nullptr)},
         {"not_fitted", f.result ? nlohmann::json(nullptr) : nlohmann::json(f.not_fitted)}});
  }
  md += fits_markdown(fits);

  // 2. Per group: its curves, the SCI crater under its law, and rates and ages where the law reaches other
  // impactor sizes.
  say(options.progress, "the SCI crater, rates and ages under the fitted laws");
  std::string sci_md =
      "\n## The SCI crater under the fitted laws\n\n2 kg at 2000 m/s into each group's target (its first "
      "row's density) under g = 1.4e-4 m/s^2, by its fitted law; observed 7.25 +- 0.8 m (Arakawa et "
      "al. 2020).\n\n" +
      sci_under_law_header(kReportCohesions);
  std::string rates_md, ages_md, not_dated;
  bool any_fit = false, any_dated = false, any_points = false;
  nlohmann::json groups_json = nlohmann::json::array();
  for (const auto& table_fits : fits) {
    if (!table_fits.result) continue;
    for (const auto& group : table_fits.result->groups) {
      nlohmann::json g = group_fit_json(table_fits, group);
      g["curves"] = scaled_radius_curves(*table_fits.table, group);
      any_points = any_points || (group.fit && g["curves"].contains("pi2_grid"));
      const std::string label = law_label(fits, table_fits, group);
      g["label"] = label;
      g["key_label"] = key_label(group.key);
      if (group.fit) {
        any_fit = true;
        const auto law = group.fit->law();
        try {
          g["sci"] =
              sci_under_law(law, table_fits.table->rows[group.rows.front()].target.density, kReportCohesions);
          sci_md += sci_under_law_row(label, g["sci"]);
        } catch (const std::exception& error) {
          // A law far from its data may have no finite answer here: say so, go on with the others.
          g.erase("sci");
          g["sci_not_computed"] = error.what();
          sci_md += fmt::format("| {} | not computed: {} |\n", label, error.what());
        }
        if (distinct_pi2(*table_fits.table, group) < 2) {
          g["rates_and_ages_not_computed"] =
              "the group's rows have one pi_2 (one impactor size, speed and gravity): its fit does not "
              "say how craters scale to the impactors of other sizes that rates and ages need";
          not_dated += fmt::format("\n- {}: one pi_2 only.", label);
        } else {
          try {
            std::string r, a;
            g["rates"] = ryugu_rates(law, kReportCohesions, r);
            g["ages"] = ryugu_ages(law, kReportCohesions, a);
            rates_md += fmt::format("\n### {}\n\n", label) + r;
            ages_md += fmt::format("\n### {}\n\n", label) + a;
            any_dated = true;
          } catch (const std::exception& error) {
            // A law far from its data may need impactors outside the population's table: say so, go on.
            g.erase("rates");
            g["rates_and_ages_not_computed"] = error.what();
            not_dated += fmt::format("\n- {}: {}", label, error.what());
          }
        }
      }
      groups_json.push_back(g);
    }
  }
  md += any_fit ? sci_md : "\n## The SCI crater under the fitted laws\n\nNo group was fitted.\n";

  // 3. The engine's SCI craters.
  std::vector<const scaling::RadiiTable*> pointers;
  for (const auto& t : tables) pointers.push_back(&t);
  json["sci_engine"] = engine_sci_against_cohesion(pointers, md);
  json["friction"] = engine_sci_against_friction(pointers, md);

  // 4. Rates and ages.
  md += fmt::format(
      "\n## Crater-formation rates on Ryugu\n\nRate of craters larger than D (rim-to-rim) per unit time, "
      "relative to {:g} Pa, under each fitted law: the main-belt population main_belt_approx_bottke2005 and "
      "collision environment, impactor density 2600 kg/m^3, rim diameter = 1.2 apparent diameters (the "
      "defaults of `craterkit rates --body ryugu`).\n",
      kReferenceCohesion);
  md += any_dated ? rates_md : "\nNo law was fitted to more than one pi_2.\n";
  md +=
      "\n## Model ages of the Ryugu counts\n\nPoisson-likelihood model ages (median and 1-sigma range) of "
      "the real counts of Ryugu's whole surface (Hirata et al. 2020, data/craters/README.md): "
      "N(>=20 m) = 77, and the same count split into 20-100 m and >= 100 m, with the production of the "
      "rates above (as `craterkit age COUNT --body ryugu`, with --max-diameter 99 or --min-diameter 100 "
      "for the split). The absolute ages rest on an approximation of the main-belt population and are "
      "indicative only; their "
      "ratios between cohesions do not depend on its normalisation (docs/chronology.md).\n";
  md += any_dated ? ages_md : "\nNo law was fitted to more than one pi_2.\n";
  if (!not_dated.empty()) md += "\nNo rates or ages under these laws:" + not_dated + "\n";

  json["producer"] = options.producer;
  json["title"] = options.title;
  json["tables"] = tables_json;
  json["fit_options"] = fit_options_json(options);
  json["published"] = published_laws_json();
  json["cohesions"] = kReportCohesions;
  json["reference_cohesion"] = kReferenceCohesion;
  json["groups"] = groups_json;
  for (const auto& [key, value] : options.extra.items()) json[key] = value;

  const auto has_series = [&](const char* section) { return !json[section]["series"].empty(); };
  if (any_points) {
    report.figures.push_back(
        {"scaled_radius.png",
         "the engine's craters as scaled radius pi_R against pi_2, one colour per cohesion, with the fitted "
         "law at each cohesion (lines), the published sand law (hh2011_sand, gravity regime, dashed) and "
         "perlite-sand law (hh2011_perlite_sand, strength regime, dotted, one level per cohesion); one panel "
         "per fitted group"});
  }
  if (has_series("sci_engine")) {
    report.figures.push_back(
        {"sci_cohesion.png",
         "the engine's SCI crater radius against cohesion per table and target, with the "
         "observed 7.25 +- 0.8 m (grey band)"});
  }
  if (has_series("friction")) {
    report.figures.push_back({"friction.png",
                              "the engine's cohesionless SCI crater radius against the friction coefficient "
                              "per table and target, with the observed band"});
  }
  if (any_dated) {
    report.figures.push_back({"rates.png",
                              "crater-formation rates on Ryugu relative to 1 Pa against crater diameter, one "
                              "line per cohesion; one panel per fitted law"});
    report.figures.push_back({"ages.png",
                              "probability densities of the model ages of the Ryugu counts, one line per "
                              "cohesion; one row of panels per fitted law"});
  }
  return report;
}

WrittenReport write_report(const Report& report, const std::filesystem::path& dir, bool progress) {
  WrittenReport out;
  for (const auto& [name, content] : report.fit_files) {
    write_text_atomically(dir / name, with_version(content).dump(2) + "\n");
    out.files.push_back(dir / name);
  }
  // The figures are drawn from report.json; it is written again with what became of them.
  const auto json_path = dir / "report.json";
  write_text_atomically(json_path, with_version(report.json).dump(2) + "\n");
  if (!report.figures.empty()) say(progress, fmt::format("drawing {} figures", report.figures.size()));
  out.figures = draw_report_figures(json_path, dir, report.figures);
  if (!out.figures.skipped.empty()) {
    std::string names;
    for (const auto& f : out.figures.skipped) names += (names.empty() ? "" : ", ") + f.file;
    std::cerr << "craterkit: figures skipped (" << names << "): " << out.figures.why << "\n";
  }
  nlohmann::json json = report.json;
  nlohmann::json drawn = nlohmann::json::array(), skipped = nlohmann::json::array();
  for (const auto& f : out.figures.drawn) drawn.push_back(f.file);
  for (const auto& f : out.figures.skipped) skipped.push_back(f.file);
  json["figures"] = {{"drawn", drawn}, {"skipped", skipped}, {"why_skipped", out.figures.why}};
  out.json = with_version(json).dump(2) + "\n";
  write_text_atomically(json_path, out.json);
  out.files.push_back(json_path);
  out.markdown = report.markdown + figures_markdown(out.figures);
  write_text_atomically(dir / "report.md", out.markdown);
  out.files.push_back(dir / "report.md");
  for (const auto& f : out.figures.drawn) out.files.push_back(dir / f.file);
  return out;
}

void print_written_report(const WrittenReport& written, bool json) {
  if (json) {
    std::cout << written.json;
    return;
  }
  std::cout << written.markdown;
  std::string files;
  for (const auto& f : written.files) files += (files.empty() ? "" : ", ") + f.string();
  fmt::print("\nwritten: {}\n", files);
}

bool is_report_output(const std::string& name) {
  if (name == "report.md" || name == "report.json" || name == "fit.json") return true;
  if (name.starts_with("fit_") && name.ends_with(".json")) return true;
  const auto& figures = report_figure_files();
  if (std::find(figures.begin(), figures.end(), name) != figures.end()) return true;
  // Temporary files of the atomic writes (".report.md.tmp.123") and of the plotting script
  // ("ages.png.tmp.png").
  return (name.starts_with(".") && name.find(".tmp.") != std::string::npos) || name.ends_with(".tmp.png");
}

}  // namespace craterkit::cli
