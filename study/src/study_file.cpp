#include "craterkit/study/study_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <utility>

#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/common/toml_table.hpp"
#include "craterkit/study/toml_document.hpp"
#include "toml_emit.hpp"

namespace craterkit::study {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// A value of [grid] or of a [[runs]] entry with its full key: sub-tables are flattened, so that
// `impact.grading = [...]` and `"impact.grading" = [...]` are the same axis.
struct Leaf {
  std::string key;
  const toml::node* node;
};

void flatten(const toml::table& table, const std::string& prefix, std::vector<Leaf>& out,
             const std::string& where) {
  for (const auto& [key, value] : table) {
    const std::string full = prefix + std::string(key.str());
    if (const auto* sub = value.as_table()) {
      if (sub->empty()) throw InputError(where + "." + full + ": an empty table is not an axis");
      flatten(*sub, full + ".", out, where);
    } else {
      out.push_back({full, &value});
    }
  }
}

// The leaves of a table in the order of the file.
std::vector<Leaf> leaves_in_order(const toml::table& table, const std::string& where) {
  std::vector<Leaf> out;
  flatten(table, "", out, where);
  std::stable_sort(out.begin(), out.end(), [](const Leaf& a, const Leaf& b) {
    const auto& sa = a.node->source().begin;
    const auto& sb = b.node->source().begin;
    return std::pair(sa.line, sa.column) < std::pair(sb.line, sb.column);
  });
  return out;
}

std::optional<double> number_of(const toml::node& node) {
  if (node.is_floating_point()) return node.as_floating_point()->get();
  if (node.is_integer()) return static_cast<double>(node.as_integer()->get());
  return std::nullopt;
}

// One value of an axis; `where` names it ("study.toml: grid.cohesion").
AxisValue axis_value(const std::string& key, AxisKind kind, const toml::node& node, const std::string& where,
                     bool sizing_enabled) {
  AxisValue v;
  v.key = key;
  v.kind = kind;
  if (const auto axis = named_axis(key)) {
    const auto number = number_of(node);
    if (!number) {
      throw InputError(where + ": expected a number (" + std::string(axis->allowed) + "), got " +
                       detail::toml_literal(node));
    }
    check_axis_value(*axis, *number, where);
    if (kind == AxisKind::resolution && !sizing_enabled) {
      throw InputError(where + ": the resolution axis needs the sizing rule ([sizing] enabled = true)");
    }
    v.number = *number;
    v.literal = toml_float(*number);
    return v;
  }
  if (const auto instead = reserved_config_key(key, sizing_enabled)) {
    throw InputError(where + ": not allowed as an axis: " + *instead);
  }
  v.literal = detail::toml_literal(node);
  if (const auto number = number_of(node)) v.number = *number;
  return v;
}

// Axes that exclude each other: projectile_mass / projectile_radius, friction / angle_of_repose.
void check_exclusive(const std::vector<std::string>& keys, const std::string& where) {
  const std::pair<const char*, const char*> pairs[] = {{"projectile_mass", "projectile_radius"},
                                                       {"friction", "angle_of_repose"}};
  for (const auto& [a, b] : pairs) {
    const bool has_a = std::find(keys.begin(), keys.end(), a) != keys.end();
    const bool has_b = std::find(keys.begin(), keys.end(), b) != keys.end();
    if (has_a && has_b) {
      throw InputError(where + "." + b + ": given together with " + a + "; give one of them");
    }
  }
}

Study parse_tables(const std::string& text, const std::filesystem::path& file) {
  const std::string source = file.string();
  Study study;
  study.file = std::filesystem::absolute(file).lexically_normal();
  TomlTable root = TomlTable::parse(text, source);
  {
    TomlTable s = root.table("study");
    study.name = s.text("name", file.stem().string());
    study.description = s.optional_text("description").value_or("");
    study.base_given = s.required_text(
        "base",
        "the base impact configuration: a shipped example name (data/examples) or a path relative "
        "to the study file");
    study.law = s.text("law", study.law);
    s.finish();
  }
  {
    TomlTable z = root.table("sizing");
    auto& r = study.sizing;
    r.enabled = z.boolean("enabled", r.enabled);
    r.predict_with_cohesion = z.boolean("predict_with_cohesion", r.predict_with_cohesion);
    r.domain_over_radius = z.number("domain_over_radius", r.domain_over_radius, 0.0, inf, true);
    r.spacings_across_radius = z.number("spacings_across_radius", r.spacings_across_radius, 0.0, inf, true);
    r.core_spacing_over_projectile_radius = z.number("core_spacing_over_projectile_radius",
                                                     r.core_spacing_over_projectile_radius, 0.0, inf, true);
    r.end_time_over_growth_time =
        z.number("end_time_over_growth_time", r.end_time_over_growth_time, 0.0, inf, true);
    z.finish();
  }
  root.accept("grid");
  root.accept("runs");
  root.finish();

  const toml::table document = toml::parse(text, source);
  if (const toml::node* grid = document.get("grid")) {
    if (!grid->is_table()) throw InputError(source + ": grid: expected a table [grid] of axes");
    std::vector<std::string> keys;
    for (const auto& leaf : leaves_in_order(*grid->as_table(), source + ": grid")) {
      const std::string where = source + ": grid." + leaf.key;
      GridAxis axis;
      axis.key = leaf.key;
      axis.kind = axis_kind(leaf.key, where);
      const auto* array = leaf.node->as_array();
      if (array == nullptr || array->empty()) {
        throw InputError(where + ": expected a non-empty array of values, got " +
                         detail::toml_literal(*leaf.node));
      }
      std::set<std::string> seen;
      for (const auto& element : *array) {
        axis.values.push_back(axis_value(leaf.key, axis.kind, element, where, study.sizing.enabled));
        if (!seen.insert(axis.values.back().literal).second) {
          throw InputError(where + ": value " + axis.values.back().literal +
                           " given twice (the grid would hold duplicate runs)");
        }
      }
      keys.push_back(leaf.key);
      study.grid.push_back(std::move(axis));
    }
    check_exclusive(keys, source + ": grid");
  }
  if (const toml::node* runs = document.get("runs")) {
    const auto* array = runs->as_array();
    if (array == nullptr ||
        !std::all_of(array->begin(), array->end(), [](const toml::node& n) { return n.is_table(); })) {
      throw InputError(source + ": runs: expected an array of tables ([[runs]] entries)");
    }
    for (std::size_t i = 0; i < array->size(); ++i) {
      const std::string entry = "runs[" + std::to_string(i) + "]";
      RunSpec run;
      run.origin = entry;
      std::vector<std::string> keys;
      for (const auto& leaf : leaves_in_order(*(*array)[i].as_table(), source + ": " + entry)) {
        const std::string where = source + ": " + entry + "." + leaf.key;
        const AxisKind kind = axis_kind(leaf.key, where);
        run.values.push_back(axis_value(leaf.key, kind, *leaf.node, where, study.sizing.enabled));
        keys.push_back(leaf.key);
      }
      check_exclusive(keys, source + ": " + entry);
      study.explicit_runs.push_back(std::move(run));
    }
  }
  if (study.grid.empty() && study.explicit_runs.empty()) {
    throw InputError(source + ": no runs: give a [grid] of axes and/or [[runs]] entries");
  }
  study.base = resolve_base(study.base_given, file);
  if (!std::filesystem::is_regular_file(study.base)) {
    throw InputError(source + ": study.base: '" + study.base_given +
                     "' is neither a shipped example (data/examples) nor a file (looked for " +
                     study.base.string() + ")");
  }
  return study;
}

}  // namespace

std::filesystem::path resolve_base(const std::string& base, const std::filesystem::path& study_file) {
  if (base.find('/') == std::string::npos) {
    for (const std::string& name : {base, base + ".toml"}) {
      std::error_code ec;
      const auto shipped = data_file("examples") / name;
      if (std::filesystem::is_regular_file(shipped, ec)) return shipped.lexically_normal();
    }
  }
  const std::filesystem::path path(base);
  if (path.is_absolute()) return path.lexically_normal();
  return (std::filesystem::absolute(study_file).parent_path() / path).lexically_normal();
}

Study parse_study(const std::string& text, const std::filesystem::path& file) {
  return parse_tables(text, file);
}

Study load_study(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("study file '" + file.string() + "' cannot be read (missing or not a file)");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_study(text.str(), file);
}

std::vector<RunSpec> expand_runs(const Study& study) {
  std::vector<RunSpec> runs;
  if (!study.grid.empty()) {
    std::vector<std::size_t> index(study.grid.size(), 0);
    while (true) {
      RunSpec run;
      run.origin = "grid";
      for (std::size_t a = 0; a < study.grid.size(); ++a)
        run.values.push_back(study.grid[a].values[index[a]]);
      runs.push_back(std::move(run));
      // Odometer: the last axis turns fastest.
      std::size_t a = study.grid.size();
      while (a > 0) {
        --a;
        if (++index[a] < study.grid[a].values.size()) break;
        index[a] = 0;
        if (a == 0) {
          a = study.grid.size() + 1;  // wrapped around: done
          break;
        }
      }
      if (a == study.grid.size() + 1) break;
    }
  }
  runs.insert(runs.end(), study.explicit_runs.begin(), study.explicit_runs.end());
  return runs;
}

}  // namespace craterkit::study
