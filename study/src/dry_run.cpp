#include "craterkit/study/dry_run.hpp"

#include <stdlib.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "craterkit/common/child_process.hpp"

namespace craterkit::study {

namespace {

std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string last_line(const std::string& text) {
  std::istringstream in(text);
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return last;
}

nlohmann::ordered_json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json();
}

}  // namespace

std::vector<ParticleCount> count_particles(const Study& study, const std::filesystem::path& program,
                                           int jobs) {
  std::string pattern = (std::filesystem::temp_directory_path() / "craterkit-sweep-dry-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create a temporary folder");
  const std::filesystem::path scratch = pattern;
  struct Cleanup {
    std::filesystem::path path;
    ~Cleanup() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  } cleanup{scratch};

  const StudyPlan plan = plan_study(study, scratch);
  write_plan(plan);
  std::vector<ParticleCount> counts(plan.runs.size());
  std::vector<std::pair<std::size_t, pid_t>> going;
  std::size_t next = 0;
  const auto finish = [&](std::size_t k, const ExitStatus& status) {
    const auto dir = run_directory(plan.out, plan.runs[k].name);
    if (status.success()) {
      try {
        const auto report = nlohmann::json::parse(read_file(dir / "dry_run.json"));
        counts[k].particles = report.at("particles").get<long long>();
        const auto size = [&](const char* key) {
          return report.contains(key) && report[key].is_number()
                     ? std::optional<double>(report[key].get<double>())
                     : std::nullopt;
        };
        counts[k].domain_radius = size("domain_radius");
        counts[k].particle_spacing = size("particle_spacing");
        counts[k].inner_spacing = size("inner_spacing");
        counts[k].end_time = size("end_time");
        return;
      } catch (const nlohmann::json::exception&) {
      }
    }
    counts[k].error = last_line(read_file(dir / "dry_run.log"));
    if (counts[k].error.empty()) counts[k].error = status.describe();
  };
  while (next < plan.runs.size() || !going.empty()) {
    while (next < plan.runs.size() && static_cast<int>(going.size()) < std::max(1, jobs)) {
      const auto dir = run_directory(plan.out, plan.runs[next].name);
      ChildCommand command;
      command.program = program;
      command.arguments = {"simulate", (dir / "config.toml").string(), "--dry-run", "--json", "--threads",
                           "1"};
      command.stdout_file = dir / "dry_run.json";
      command.stderr_file = dir / "dry_run.log";
      going.emplace_back(next, spawn_child(command));
      ++next;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    for (auto it = going.begin(); it != going.end();) {
      if (const auto status = poll_child(it->second)) {
        finish(it->first, *status);
        it = going.erase(it);
      } else {
        ++it;
      }
    }
  }
  return counts;
}

std::string format_dry_run(const StudyPlan& plan, const std::vector<ParticleCount>& counts, bool json) {
  if (json) {
    auto out = nlohmann::ordered_json::array();
    for (const auto& run : plan.runs) {
      nlohmann::ordered_json axes = nlohmann::ordered_json::object();
      for (const auto& v : run.values) {
        axes[v.key] = v.number ? nlohmann::ordered_json(*v.number) : nlohmann::ordered_json(v.literal);
      }
      const auto& s = run.sizing;
      nlohmann::ordered_json row = {{"index", run.index},
                                    {"name", run.name},
                                    {"axes", axes},
                                    {"sized", run.sized},
                                    {"predicted_crater_radius", number_or_null(s.predicted_crater_radius)}};
      if (run.sized) {
        row["domain_radius"] = s.domain_radius;
        row["particle_spacing"] = s.particle_spacing;
        row["inner_spacing"] = s.inner_spacing;
        row["end_time"] = s.end_time;
      }
      if (run.index < counts.size()) {
        const auto& c = counts[run.index];
        if (!run.sized) {
          const auto put = [&](const char* key, const std::optional<double>& v) {
            if (v) row[key] = *v;
          };
          put("domain_radius", c.domain_radius);
          put("particle_spacing", c.particle_spacing);
          put("inner_spacing", c.inner_spacing);
          put("end_time", c.end_time);
        }
        row["particles"] = c.particles ? nlohmann::ordered_json(*c.particles) : nlohmann::ordered_json();
        if (!c.error.empty()) row["error"] = c.error;
      }
      out.push_back(row);
    }
    return out.dump(2) + "\n";
  }
  std::string text = fmt::format(
      "study \"{}\": {} runs (law {}, sizing {}); dry run, nothing run or written\n", plan.study.name,
      plan.runs.size(), plan.study.law, plan.study.sizing.enabled ? "on" : "off");
  text += fmt::format("{:>4}  {:<44} {:>9} {:>9} {:>9} {:>9} {:>9} {:>10}\n", "#", "run", "R_pred/m",
                      "R_dom/m", "dx_max/m", "dx0/m", "end/s", "particles");
  for (const auto& run : plan.runs) {
    const auto& s = run.sizing;
    std::string count = "-";
    std::string error;
    // Sizing off: the run's own sizes from its dry run, "(base)" where there is none (no counts, or a set-up
    // that failed or is not an impact).
    std::string own[4] = {"(base)", "(base)", "(base)", "(base)"};
    if (run.index < counts.size()) {
      const auto& c = counts[run.index];
      if (c.particles) count = std::to_string(*c.particles);
      error = c.error;
      const std::optional<double> sizes[4] = {c.domain_radius, c.particle_spacing, c.inner_spacing,
                                              c.end_time};
      for (int k = 0; k < 4; ++k) {
        if (sizes[k]) own[k] = fmt::format("{:.4g}", *sizes[k]);
      }
    }
    if (run.sized) {
      text += fmt::format("{:>4}  {:<44} {:>9.4g} {:>9.4g} {:>9.4g} {:>9.4g} {:>9.4g} {:>10}\n", run.index,
                          run.name, s.predicted_crater_radius, s.domain_radius, s.particle_spacing,
                          s.inner_spacing, s.end_time, count);
    } else {
      text += fmt::format("{:>4}  {:<44} {:>9.4g} {:>9} {:>9} {:>9} {:>9} {:>10}\n", run.index, run.name,
                          s.predicted_crater_radius, own[0], own[1], own[2], own[3], count);
    }
    if (!error.empty()) text += "      set-up error: " + error + "\n";
  }
  return text;
}

}  // namespace craterkit::study
