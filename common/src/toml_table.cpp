#include "craterkit/common/toml_table.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include <toml++/toml.h>

#include "craterkit/common/checks.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit {

struct TomlTable::Document {
  toml::table root;
  // What every getter returned, by dotted key (values_read()).
  mutable std::map<std::string, std::string> values;
};

namespace {

const toml::table* as_table(const void* table) {
  return static_cast<const toml::table*>(table);
}
const toml::node* as_node(const void* node) {
  return static_cast<const toml::node*>(node);
}

// A value as text: numbers with every digit, so that two values that differ print differently.
std::string value_text(double x) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

}  // namespace

void TomlTable::record(std::string_view k, std::string value) const {
  document_->values[key(k)] = std::move(value);
}

std::string TomlTable::values_read() const {
  std::string out;
  for (const auto& [k, v] : document_->values) out += k + " = " + v + "\n";
  return out;
}

TomlTable::TomlTable(std::shared_ptr<const Document> document, const void* table, std::string name,
                     std::string source)
    : document_(std::move(document)), table_(table), name_(std::move(name)), source_(std::move(source)) {}

TomlTable TomlTable::parse(const std::string& text, const std::string& source) {
  auto document = std::make_shared<Document>();
  try {
    document->root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << source << ":" << e.source().begin.line << ":" << e.source().begin.column
      << ": TOML syntax error: " << e.description();
    throw InputError(s.str());
  }
  const void* root = &document->root;
  return TomlTable(std::move(document), root, "", source);
}

TomlTable TomlTable::parse_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("cannot read " + file.string());
  std::ostringstream text;
  text << in.rdbuf();
  return parse(text.str(), file.string());
}

std::string TomlTable::key(std::string_view k) const {
  return name_.empty() ? std::string(k) : name_ + "." + std::string(k);
}

void TomlTable::fail(std::string_view k, const std::string& what) const {
  throw InputError(source_ + ": " + key(k) + ": " + what);
}

const void* TomlTable::find(std::string_view k) const {
  return table_ == nullptr ? nullptr : as_table(table_)->get(k);
}

const void* TomlTable::use(std::string_view k) {
  used_.insert(std::string(k));
  return find(k);
}

bool TomlTable::contains(std::string_view k) const {
  return find(k) != nullptr;
}

std::vector<std::string> TomlTable::keys() const {
  std::vector<std::string> out;
  if (table_ == nullptr) return out;
  for (const auto& [k, node] : *as_table(table_)) out.emplace_back(k.str());
  return out;
}

namespace {

double number_of(const toml::node& node, const TomlTable& table, std::string_view k) {
  if (node.is_floating_point()) return node.as_floating_point()->get();
  if (node.is_integer()) return static_cast<double>(node.as_integer()->get());
  table.fail(k, "expected a number");
}

}  // namespace

double TomlTable::number(std::string_view k, double fallback, double lo, double hi, bool lo_open,
                         bool hi_open) {
  const auto* node = as_node(use(k));
  if (node == nullptr) {
    record(k, value_text(fallback));
    return fallback;
  }
  const double x = number_of(*node, *this, k);
  if (!in_range(x, lo, hi, lo_open, hi_open)) out_of_range(k, x, range_text(lo, hi, lo_open, hi_open));
  record(k, value_text(x));
  return x;
}

std::optional<double> TomlTable::optional_number(std::string_view k, double lo, double hi, bool lo_open,
                                                 bool hi_open) {
  if (find(k) == nullptr) {
    used_.insert(std::string(k));
    record(k, "(absent)");
    return std::nullopt;
  }
  return number(k, 0.0, lo, hi, lo_open, hi_open);
}

double TomlTable::required_number(std::string_view k, double lo, double hi, bool lo_open, bool hi_open) {
  const auto x = optional_number(k, lo, hi, lo_open, hi_open);
  if (!x) fail(k, "missing: a number in " + range_text(lo, hi, lo_open, hi_open));
  return *x;
}

void TomlTable::out_of_range(std::string_view k, double value, const std::string& allowed) const {
  fail(k, out_of_range_text(value, allowed));
}

std::int64_t TomlTable::integer(std::string_view k, std::int64_t fallback, std::int64_t lo, std::int64_t hi) {
  const auto* node = as_node(use(k));
  if (node == nullptr) {
    record(k, std::to_string(fallback));
    return fallback;
  }
  if (!node->is_integer()) fail(k, "expected an integer");
  const std::int64_t x = node->as_integer()->get();
  if (x < lo || x > hi) {
    fail(k, "value " + std::to_string(x) + " out of range: allowed [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "]");
  }
  record(k, std::to_string(x));
  return x;
}

bool TomlTable::boolean(std::string_view k, bool fallback) {
  const auto* node = as_node(use(k));
  if (node != nullptr && !node->is_boolean()) fail(k, "expected true or false");
  const bool value = node == nullptr ? fallback : node->as_boolean()->get();
  record(k, value ? "true" : "false");
  return value;
}

std::optional<std::string> TomlTable::optional_text(std::string_view k,
                                                    const std::vector<std::string>& allowed) {
  const auto* node = as_node(use(k));
  if (node == nullptr) {
    record(k, "(absent)");
    return std::nullopt;
  }
  if (!node->is_string()) fail(k, "expected a string");
  std::string v = node->as_string()->get();
  if (!allowed.empty()) {
    bool ok = false;
    std::string list;
    for (const auto& a : allowed) {
      ok = ok || a == v;
      list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
    }
    if (!ok) fail(k, "value \"" + v + "\" not allowed: one of " + list);
  }
  if (v.empty()) fail(k, "must not be empty");
  record(k, "\"" + v + "\"");
  return v;
}

std::string TomlTable::text(std::string_view k, const std::string& fallback,
                            const std::vector<std::string>& allowed) {
  auto v = optional_text(k, allowed);
  if (!v) record(k, "\"" + fallback + "\"");
  return v.value_or(fallback);
}

std::string TomlTable::required_text(std::string_view k, const std::string& what,
                                     const std::vector<std::string>& allowed) {
  auto v = optional_text(k, allowed);
  if (!v) fail(k, "missing: " + what);
  return *v;
}

std::optional<std::vector<double>> TomlTable::numbers(std::string_view k, std::optional<std::size_t> count,
                                                      bool allow_infinite) {
  const auto* node = as_node(use(k));
  if (node == nullptr) {
    record(k, "(absent)");
    return std::nullopt;
  }
  const std::string expected =
      count ? "an array of " + std::to_string(*count) + " numbers" : std::string("an array of numbers");
  const toml::array* array = node->as_array();
  if (array == nullptr) fail(k, "expected " + expected);
  if (count && array->size() != *count) {
    fail(k, "expected " + std::to_string(*count) + " numbers, got " + std::to_string(array->size()));
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& e = *array->get(i);
    if (!e.is_floating_point() && !e.is_integer())
      fail(k, "element " + std::to_string(i) + " is not a number");
    const double v = number_of(e, *this, k);
    if (std::isnan(v) || (!allow_infinite && !std::isfinite(v))) {
      fail(k, "element " + std::to_string(i) + " is not finite");
    }
    out.push_back(v);
  }
  std::string listed;
  for (const double v : out) listed += (listed.empty() ? "" : ", ") + value_text(v);
  record(k, "[" + listed + "]");
  return out;
}

std::vector<double> TomlTable::required_numbers(std::string_view k, std::optional<std::size_t> count,
                                                bool allow_infinite) {
  auto v = numbers(k, count, allow_infinite);
  if (!v)
    fail(k, "missing: an array of " + (count ? std::to_string(*count) + " " : std::string()) + "numbers");
  return *v;
}

std::optional<std::vector<std::string>> TomlTable::texts(std::string_view k) {
  const auto* node = as_node(use(k));
  if (node == nullptr) {
    record(k, "(absent)");
    return std::nullopt;
  }
  const toml::array* array = node->as_array();
  if (array == nullptr) fail(k, "expected an array of strings");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& e = *array->get(i);
    if (!e.is_string() || e.as_string()->get().empty()) {
      fail(k, "element " + std::to_string(i) + " is not a non-empty string");
    }
    out.push_back(e.as_string()->get());
  }
  std::string listed;
  for (const auto& v : out) listed += (listed.empty() ? "\"" : ", \"") + v + "\"";
  record(k, "[" + listed + "]");
  return out;
}

bool TomlTable::is_table(std::string_view k) const {
  const auto* node = as_node(find(k));
  return node != nullptr && node->is_table();
}

TomlTable TomlTable::table(std::string_view k) {
  const auto* node = as_node(use(k));
  if (node != nullptr && !node->is_table()) fail(k, "must be a table ([" + key(k) + "])");
  return TomlTable(document_, node == nullptr ? nullptr : node->as_table(), key(k), source_);
}

TomlTable TomlTable::required_table(std::string_view k) {
  if (find(k) == nullptr) fail(k, "missing: a table ([" + key(k) + "])");
  return table(k);
}

std::vector<TomlTable> TomlTable::tables(std::string_view k) {
  const auto* node = as_node(use(k));
  std::vector<TomlTable> out;
  if (node == nullptr) return out;
  const toml::array* array = node->as_array();
  if (array == nullptr) fail(k, "expected an array of tables ([[" + key(k) + "]])");
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& e = *array->get(i);
    const std::string name = key(k) + "[" + std::to_string(i) + "]";
    if (!e.is_table()) throw InputError(source_ + ": " + name + ": must be a table");
    out.push_back(TomlTable(document_, e.as_table(), name, source_));
  }
  return out;
}

namespace {

// Throws for the first key of `table` not in `allowed`, listing the allowed ones.
void reject_keys_outside(const TomlTable& table, const toml::table* keys,
                         const std::set<std::string>& allowed) {
  if (keys == nullptr) return;
  for (const auto& [k, node] : *keys) {
    const std::string name(k.str());
    if (allowed.count(name) == 0) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw InputError(
          table.source() + ": unknown key " + table.key(name) +
          (list.empty() ? std::string(" (no keys are allowed here)") : " (allowed here: " + list + ")"));
    }
  }
}

}  // namespace

void TomlTable::finish() const {
  reject_keys_outside(*this, as_table(table_), used_);
}

void TomlTable::reject_unknown(const std::vector<std::string>& allowed) const {
  reject_keys_outside(*this, as_table(table_), {allowed.begin(), allowed.end()});
}

}  // namespace craterkit
