#include "craterkit/study/sweep_tables.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::study {

namespace {

std::string number(double value) {
  return fmt::format("{:.17g}", value);
}

// A CSV cell: quoted when it holds a comma, a quote or a line break.
std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string one_line(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return text;
}

// One CSV line.
std::string join(const std::vector<std::string>& cells) {
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i > 0) line += ',';
    line += cells[i];
  }
  line += '\n';
  return line;
}

std::string optional_number(bool present, double value) {
  return present ? number(value) : "";
}

}  // namespace

std::vector<std::string> radii_columns(const std::vector<std::string>& extra_columns) {
  std::vector<std::string> columns = {
      "impactor_radius", "impactor_density",    "velocity", "target_density", "gravity",   "strength",
      "crater_radius",   "crater_radius_sigma", "friction", "porosity",       "resolution"};
  columns.insert(columns.end(), extra_columns.begin(), extra_columns.end());
  columns.push_back("run");
  columns.push_back("growth_ended");
  return columns;
}

std::string format_radii_csv(const TableHeader& header, const std::vector<std::string>& extra_columns,
                             const std::vector<RadiiRow>& rows) {
  std::string out;
  out += "# craterkit sweep: study \"" + one_line(header.study_name) + "\"" +
         (header.description.empty() ? "" : ": " + one_line(header.description)) + "\n";
  out += "# " + one_line(header.producer) + "\n";
  out += "# command: " + one_line(header.command) + "\n";
  std::vector<std::string> cells = radii_columns(extra_columns);
  for (auto& cell : cells) cell = csv_cell(cell);
  out += join(cells);
  for (const auto& r : rows) {
    cells.clear();
    for (const double v :
         {r.impactor_radius, r.impactor_density, r.velocity, r.target_density, r.gravity, r.strength,
          r.crater_radius, r.crater_radius_sigma, r.friction, r.porosity, r.resolution}) {
      cells.push_back(number(v));
    }
    for (const auto& cell : r.extra) cells.push_back(csv_cell(cell));
    cells.push_back(csv_cell(r.run));
    cells.push_back(r.growth_ended ? "true" : "false");
    out += join(cells);
  }
  return out;
}

std::string format_runs_csv(const std::vector<RunRecord>& runs) {
  std::string out =
      "run,status,attempts,crater_radius,crater_radius_sigma,growth_ended,particles,steps,simulated_time,"
      "wall_seconds,cost_seconds,failure\n";
  for (const auto& r : runs) {
    const auto& res = r.result;
    const bool crater = res && res->has_crater;
    out += join({csv_cell(r.name), to_string(r.status), std::to_string(r.attempts),
                 optional_number(crater, crater ? res->row.crater_radius : 0.0),
                 optional_number(crater, crater ? res->row.crater_radius_sigma : 0.0),
                 res ? (res->row.growth_ended ? "true" : "false") : "",
                 res ? std::to_string(res->particles) : "", res ? std::to_string(res->steps) : "",
                 optional_number(res.has_value(), res ? res->simulated_time : 0.0),
                 optional_number(res.has_value(), res ? res->wall_seconds : 0.0),
                 optional_number(res.has_value(), res ? res->cost_seconds : 0.0),
                 csv_cell(r.status == RunStatus::failed && r.failure ? r.failure->description : "")});
  }
  return out;
}

CollectReport collect(const std::filesystem::path& out, const std::string& producer) {
  const auto plan_file = out / "sweep.json";
  std::ifstream in(plan_file);
  if (!in) {
    throw InputError("--collect " + out.string() +
                     ": no sweep.json there: not the output folder of a craterkit sweep");
  }
  nlohmann::ordered_json plan;
  try {
    plan = nlohmann::ordered_json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(plan_file.string() + ": not readable JSON: " + e.what());
  }
  CollectReport report;
  report.header.study_name = plan["study"].value("name", "");
  report.header.description = plan["study"].value("description", "");
  report.header.producer = producer;
  report.header.command = plan.value("command", "");
  const auto extra_columns = plan.value("extra_columns", std::vector<std::string>{});
  std::vector<RadiiRow> rows;
  for (const auto& name : plan.at("runs")) {
    RunRecord record = inspect_run(out, name.get<std::string>());
    if (record.result && record.result->has_crater &&
        record.result->row.extra.size() == extra_columns.size()) {
      rows.push_back(record.result->row);
    }
    report.runs.push_back(std::move(record));
  }
  report.rows = rows.size();
  report.radii_csv = out / "radii.csv";
  report.runs_csv = out / "runs.csv";
  write_text_atomically(report.radii_csv, format_radii_csv(report.header, extra_columns, rows));
  write_text_atomically(report.runs_csv, format_runs_csv(report.runs));
  return report;
}

std::string format_collect_summary(const CollectReport& report, long long started, bool json) {
  std::size_t done = 0, no_crater = 0, failed = 0, other = 0;
  for (const auto& r : report.runs) {
    if (r.status == RunStatus::done)
      ++done;
    else if (r.status == RunStatus::no_crater)
      ++no_crater;
    else if (r.status == RunStatus::failed)
      ++failed;
    else
      ++other;
  }
  if (json) {
    auto runs = nlohmann::ordered_json::array();
    for (const auto& r : report.runs) {
      nlohmann::ordered_json row = {
          {"name", r.name}, {"status", to_string(r.status)}, {"attempts", r.attempts}};
      if (r.result && r.result->has_crater) {
        row["crater_radius"] = r.result->row.crater_radius;
        row["crater_radius_sigma"] = r.result->row.crater_radius_sigma;
        row["growth_ended"] = r.result->row.growth_ended;
      }
      if (r.status == RunStatus::failed && r.failure) row["failure"] = r.failure->description;
      runs.push_back(row);
    }
    nlohmann::ordered_json out = {{"study", report.header.study_name},
                                  {"runs_total", report.runs.size()},
                                  {"done", done},
                                  {"no_crater", no_crater},
                                  {"failed", failed},
                                  {"not_finished", other},
                                  {"radii_csv", report.radii_csv.string()},
                                  {"radii_rows", report.rows},
                                  {"runs_csv", report.runs_csv.string()}};
    if (started >= 0) out["started"] = started;
    out["runs"] = runs;
    return out.dump(2) + "\n";
  }
  std::string text = fmt::format(
      "sweep: study \"{}\": {} runs: {} done with a crater, {} without, {} failed, {} not finished\n",
      report.header.study_name, report.runs.size(), done, no_crater, failed, other);
  text +=
      fmt::format("  {} ({} rows), {}\n", report.radii_csv.string(), report.rows, report.runs_csv.string());
  for (const auto& r : report.runs) {
    if (r.status == RunStatus::failed) {
      text += fmt::format("  failed: {} ({}; see runs/{}/failed.json)\n", r.name,
                          r.failure ? r.failure->description : "unknown", r.name);
    }
  }
  return text;
}

}  // namespace craterkit::study
