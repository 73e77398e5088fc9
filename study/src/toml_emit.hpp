#pragma once
// TOML text of toml++ nodes (internal to the study library): one writer for run configurations, target
// materials and the axis values of a study, so that equal values always give equal text.
#include <toml++/toml.h>

#include <string>

namespace craterkit::study::detail {

// A key, bare when it can be ("grading"), else quoted ("\"impact.grading\"").
std::string toml_key(std::string_view key);
// An inline value: numbers, strings, booleans, dates, arrays, inline tables.
std::string toml_literal(const toml::node& node);
// A whole table as a document (path "" for the root).
void dump_table(std::string& out, const toml::table& table, const std::string& path);
// Parses "v = <text>" and returns the value; InputError naming `what` when the text is not one TOML value.
toml::table parse_literal(std::string_view text, const std::string& what);

}  // namespace craterkit::study::detail
