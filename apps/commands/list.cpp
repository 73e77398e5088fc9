// craterkit list [constant-sets|bodies|materials|populations|studies]: the data sets shipped in the data
// directory, each with its file, what it describes and where its values come from.
#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "craterkit/chronology/body.hpp"
#include "craterkit/chronology/chronology_system.hpp"
#include "craterkit/chronology/population.hpp"
#include "craterkit/common/data_catalogue.hpp"
#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/common/toml_table.hpp"
#include "craterkit/scaling/constant_sets.hpp"
#include "json_output.hpp"

namespace craterkit::cli {
namespace {

struct Entry {
  std::string name;
  std::string description;
  std::string citation;
  std::filesystem::path file;
};

struct Category {
  const char* name;    // as typed on the command line
  const char* folder;  // under the data directory
  const char* title;
};

const std::vector<Category>& categories() {
  static const std::vector<Category> all = {
      {"constant-sets", "scaling", "scaling-law constant sets (--params NAME)"},
      {"bodies", "bodies", "target bodies (--body NAME)"},
      {"materials", "materials", "materials (material = \"NAME\" in a configuration)"},
      {"populations", "populations", "impactor populations (--population NAME)"},
      {"chronology-systems", "chronology", "chronology systems (craterkit age --chronology NAME)"},
      {"studies", "studies", "studies (craterkit sweep FILE)"},
  };
  return all;
}

std::string optional_text(TomlTable& table, const char* key) {
  return table.contains(key) ? table.optional_text(key).value_or("") : "";
}

Entry describe(const Category& category, const std::string& name) {
  Entry entry;
  entry.name = name;
  entry.file = data_file(category.folder) / (name + ".toml");
  const std::string kind = category.name;
  if (kind == "constant-sets") {
    const auto set = scaling::load_constant_set(name);
    entry.description = set.description;
    entry.citation = set.citation;
  } else if (kind == "bodies") {
    const auto body = chronology::load_body(name);
    entry.description = fmt::format("{}: mean radius {:g} m, bulk density {:g} kg/m^3, gravity {:.4g} m/s^2",
                                    body.name, body.mean_radius, body.bulk_density, body.surface_gravity);
    entry.citation = body.citations;
  } else if (kind == "populations") {
    const auto population = chronology::load_population(name);
    entry.description = population.notes + (population.approximate ? " (approximate shape)" : "");
    entry.citation = population.citation;
  } else if (kind == "chronology-systems") {
    const auto system = chronology::load_chronology_system(name);
    entry.description = system.title + " (" + system.body + ")";
    entry.citation = system.citation;
  } else if (kind == "materials") {
    auto table = TomlTable::parse_file(entry.file);
    entry.description = optional_text(table, "description");
    entry.citation = optional_text(table, "citation");
  } else {
    auto table = TomlTable::parse_file(entry.file);
    auto study = table.table("study");
    entry.description = optional_text(study, "description");
    const std::string law = optional_text(study, "law");
    entry.citation = law.empty() ? "craterkit simulations" : "craterkit simulations sized by the law " + law;
  }
  // Multi-line citations (a body's one line per value) print as one line each in text, stay as they are in
  // JSON.
  while (!entry.citation.empty() && entry.citation.back() == '\n') entry.citation.pop_back();
  return entry;
}

struct ListOptions {
  std::optional<std::string> category;
  bool json = false;
};

void run_list(const ListOptions& options) {
  std::vector<const Category*> wanted;
  for (const auto& c : categories()) {
    if (!options.category || *options.category == c.name) wanted.push_back(&c);
  }
  nlohmann::json out;
  out["data_directory"] = data_directory().string();
  out["data_origin"] = data_directory_origin();
  if (!options.json)
    fmt::print("data directory: {} ({})\n", data_directory().string(), data_directory_origin());
  for (const Category* category : wanted) {
    std::string key = category->name;
    for (auto& ch : key) ch = ch == '-' ? '_' : ch;
    nlohmann::json entries = nlohmann::json::array();
    if (!options.json) fmt::print("\n{}:\n", category->title);
    for (const auto& name : data_set_names(category->folder)) {
      const Entry entry = describe(*category, name);
      entries.push_back({{"name", entry.name},
                         {"description", entry.description},
                         {"citation", entry.citation},
                         {"source", entry.file.string()}});
      if (options.json) continue;
      fmt::print("  {}\n    {}\n    source: {}\n", entry.name, entry.description, entry.file.string());
      std::string citation = entry.citation;
      std::size_t start = 0;
      bool first = true;
      while (start < citation.size()) {
        const std::size_t end = std::min(citation.find('\n', start), citation.size());
        fmt::print("    {}{}\n", first ? "citation: " : "          ", citation.substr(start, end - start));
        first = false;
        start = end + 1;
      }
    }
    out[key] = entries;
  }
  if (options.json) print_json(out);
}

void add_list_command(CLI::App& parent) {
  auto options = std::make_shared<ListOptions>();
  auto* sub = parent.add_subcommand(
      "list",
      "List the shipped data sets (constant sets, bodies, materials, populations, studies) with their "
      "files and citations");
  std::vector<std::string> names;
  for (const auto& c : categories()) names.emplace_back(c.name);
  sub->add_option(
         "what", options->category,
         "Only this kind: constant-sets, bodies, materials, populations, chronology-systems, studies")
      ->check(CLI::IsMember(names));
  sub->add_flag("--json", options->json, "Print a JSON object instead of text");
  sub->footer("The data directory is CRATERKIT_DATA_DIR when set, else the installation's share/craterkit.");
  sub->callback([options] { run_list(*options); });
}

const bool list_registered = register_command({"list", 5, &add_list_command});

}  // namespace
}  // namespace craterkit::cli
