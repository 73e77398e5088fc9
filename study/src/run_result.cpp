#include "craterkit/study/run_result.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "craterkit/study/run_lock.hpp"

namespace craterkit::study {

namespace {

using json = nlohmann::ordered_json;

std::optional<std::string> read_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

double number_or_nan(const json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : NAN;
}

json number_or_null(double v) {
  return std::isfinite(v) ? json(v) : json();
}

}  // namespace

std::string to_string(RunStatus status) {
  switch (status) {
    case RunStatus::pending:
      return "pending";
    case RunStatus::interrupted:
      return "interrupted";
    case RunStatus::running:
      return "running";
    case RunStatus::done:
      return "done";
    case RunStatus::no_crater:
      return "no_crater";
    case RunStatus::failed:
      return "failed";
  }
  return "unknown";
}

std::string make_result_json(const StudyPlan& plan, const PlannedRun& run, const std::string& summary_text,
                             const std::string& crater_text, double wall_seconds, int attempts) {
  json summary, crater;
  try {
    summary = json::parse(summary_text);
    crater = json::parse(crater_text);
  } catch (const json::parse_error& e) {
    throw std::runtime_error(std::string("the run's summary or crater.json is not JSON: ") + e.what());
  }
  if (!summary.is_object() || !summary.contains("particles") || !summary.contains("steps") ||
      !crater.is_object() || !crater.contains("settings")) {
    throw std::runtime_error("the run's summary or crater.json lacks what `craterkit simulate` writes");
  }
  const double radius = number_or_nan(crater, "crater_radius");
  const double sigma = number_or_nan(crater, "crater_radius_uncertainty");
  const double target_density = number_or_nan(crater["settings"], "rho_initial");
  const bool growth_ended = summary.value("crater_growth_ended", false);
  json extra = json::object();
  for (std::size_t c = 0; c < plan.extra_columns.size(); ++c) {
    std::string cell = run.extra_cells[c];
    // The default rule's transition time is known from the run: its summary.
    if (plan.extra_columns[c] == "t_transition" && cell.empty() && summary.contains("late_stage")) {
      char text[64];
      std::snprintf(text, sizeof(text), "%.17g", summary["late_stage"].value("transition_time", 0.0));
      cell = text;
    }
    extra[plan.extra_columns[c]] = cell;
  }
  const long long steps = summary.value("steps", 0LL);
  const long long steps_this_run = summary.value("steps_this_run", 0LL);
  const double child_wall = summary.value("wall_seconds", 0.0);
  const double cost = steps_this_run > 0
                          ? child_wall * static_cast<double>(steps) / static_cast<double>(steps_this_run)
                          : 0.0;
  json out = {
      {"run", run.name},
      {"status", std::isfinite(radius) ? "done" : "no_crater"},
      {"row",
       {{"impactor_radius", run.impactor_radius},
        {"impactor_density", run.impactor_density},
        {"velocity", run.velocity},
        {"target_density", number_or_null(target_density)},
        {"gravity", run.gravity},
        {"strength", run.cohesion},
        {"crater_radius", number_or_null(radius)},
        {"crater_radius_sigma", number_or_null(sigma)},
        {"friction", run.friction},
        {"porosity", run.porosity},
        {"resolution", number_or_null(run.resolution)},
        {"extra", extra},
        {"growth_ended", growth_ended}}},
      {"crater",
       {{"crater_radius", number_or_null(radius)},
        {"crater_radius_uncertainty", number_or_null(sigma)},
        {"depth", number_or_null(number_or_nan(crater, "depth"))},
        {"growth_ended", growth_ended},
        {"growth_end_time", summary.value("crater_growth_end_time", json())},
        {"growth_end_radius", summary.value("crater_growth_end_radius", json())}}},
      {"particles", summary["particles"]},
      {"steps", steps},
      {"simulated_time", summary.value("time", 0.0)},
      {"wall_seconds", wall_seconds},
      {"cost_seconds", cost},
      {"attempts", attempts},
      {"simulate", summary},
  };
  return out.dump(2) + "\n";
}

std::optional<RunResult> read_result(const std::filesystem::path& run_dir) {
  const auto text = read_file(run_dir / "result.json");
  if (!text) return std::nullopt;
  try {
    const json j = json::parse(*text);
    const json& row = j.at("row");
    RunResult r;
    auto& w = r.row;
    w.run = j.at("run").get<std::string>();
    w.impactor_radius = row.at("impactor_radius").get<double>();
    w.impactor_density = row.at("impactor_density").get<double>();
    w.velocity = row.at("velocity").get<double>();
    w.target_density = number_or_nan(row, "target_density");
    w.gravity = row.at("gravity").get<double>();
    w.strength = row.at("strength").get<double>();
    w.crater_radius = number_or_nan(row, "crater_radius");
    w.crater_radius_sigma = number_or_nan(row, "crater_radius_sigma");
    w.friction = row.at("friction").get<double>();
    w.porosity = row.at("porosity").get<double>();
    w.resolution = number_or_nan(row, "resolution");
    for (const auto& [key, cell] : row.at("extra").items()) w.extra.push_back(cell.get<std::string>());
    w.growth_ended = row.at("growth_ended").get<bool>();
    r.has_crater = j.at("status").get<std::string>() == "done";
    r.crater_depth = number_or_nan(j.at("crater"), "depth");
    r.particles = j.at("particles").get<long long>();
    r.steps = j.at("steps").get<long long>();
    r.simulated_time = j.at("simulated_time").get<double>();
    r.wall_seconds = j.at("wall_seconds").get<double>();
    r.cost_seconds = j.at("cost_seconds").get<double>();
    r.attempts = j.at("attempts").get<int>();
    return r;
  } catch (const json::exception&) {
    return std::nullopt;
  }
}

std::string make_failure_json(const std::string& run, const ExitStatus& status, int attempt,
                              double wall_seconds, const std::vector<std::string>& stderr_tail,
                              const std::string& message) {
  json out = {{"run", run},
              {"description", status.describe()},
              {"exit_status", status.signalled ? json() : json(status.code)},
              {"signal", status.signalled ? json(status.signal) : json()},
              {"attempt", attempt},
              {"wall_seconds", wall_seconds},
              {"message", message},
              {"stderr_tail", stderr_tail}};
  return out.dump(2) + "\n";
}

std::optional<RunFailure> read_failure(const std::filesystem::path& run_dir) {
  const auto text = read_file(run_dir / "failed.json");
  if (!text) return std::nullopt;
  RunFailure f;
  try {
    const json j = json::parse(*text);
    f.description = j.value("description", "");
    f.exit_status =
        j.contains("exit_status") && j["exit_status"].is_number() ? j["exit_status"].get<int>() : -1;
    f.attempt = j.value("attempt", 0);
    if (j.contains("stderr_tail")) f.stderr_tail = j["stderr_tail"].get<std::vector<std::string>>();
  } catch (const json::exception&) {
    f.description = "failed.json unreadable";
  }
  return f;
}

int count_attempts(const std::filesystem::path& run_dir) {
  std::ifstream in(run_dir / "attempts.log");
  int n = 0;
  std::string line;
  while (std::getline(in, line)) n += line.empty() ? 0 : 1;
  return n;
}

RunRecord inspect_run(const std::filesystem::path& out, const std::string& name) {
  const auto dir = run_directory(out, name);
  RunRecord r;
  r.name = name;
  r.attempts = count_attempts(dir);
  r.result = read_result(dir);
  if (r.result) {
    r.status = r.result->has_crater ? RunStatus::done : RunStatus::no_crater;
    return r;
  }
  r.failure = read_failure(dir);
  if (is_locked(dir / "lock")) {
    r.status = RunStatus::running;
  } else if (r.failure) {
    r.status = RunStatus::failed;
  } else if (r.attempts > 0 || std::filesystem::exists(dir / "checkpoint.h5")) {
    r.status = RunStatus::interrupted;
  } else {
    r.status = RunStatus::pending;
  }
  return r;
}

}  // namespace craterkit::study
