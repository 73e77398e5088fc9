#pragma once
// Private to sph_core: one TOML table of a configuration with typed getters that remember the keys they
// were asked for; finish() then rejects every key not read (unknown or misspelt), naming it and listing
// the allowed ones. All errors are craterkit::InputError "<source>: <table>.<key>: <what>". Shared by the
// simulation configuration (config.cpp) and the impact set-up (impact_config.cpp).
#include <cmath>
#include <cstdint>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::sph {

class TomlKeys {
 public:
  // table may be null (an absent table: every getter returns its fallback); name may be empty (root).
  TomlKeys(const toml::table* table, std::string name, std::string source)
      : table_(table), name_(std::move(name)), source_(std::move(source)) {}

  [[nodiscard]] std::string key(const std::string& k) const { return name_.empty() ? k : name_ + "." + k; }
  [[nodiscard]] const std::string& source() const { return source_; }

  [[noreturn]] void fail(const std::string& k, const std::string& what) const {
    throw InputError(source_ + ": " + key(k) + ": " + what);
  }

  const toml::node* find(const std::string& k) {
    used_.insert(k);
    return table_ == nullptr ? nullptr : table_->get(k);
  }

  // A finite number in [lo, hi] (lower bound open when lo_open).
  double number(const std::string& k, double fallback, double lo, double hi, bool lo_open = false) {
    const toml::node* node = find(k);
    if (node == nullptr) return fallback;
    const double x = as_number(*node, k);
    const bool below = lo_open ? !(x > lo) : !(x >= lo);
    if (below || !(x <= hi) || !std::isfinite(x)) {
      fail(k, "value " + format_number(x) + " out of range: allowed " + (lo_open ? "(" : "[") +
                  format_number(lo) + ", " + format_number(hi) + "]");
    }
    return x;
  }

  // As number(), but absent gives nullopt.
  std::optional<double> optional_number(const std::string& k, double lo, double hi, bool lo_open = false) {
    if (find(k) == nullptr) return std::nullopt;
    return number(k, 0.0, lo, hi, lo_open);
  }

  std::int64_t integer(const std::string& k, std::int64_t fallback, std::int64_t lo, std::int64_t hi) {
    const toml::node* node = find(k);
    if (node == nullptr) return fallback;
    if (!node->is_integer()) fail(k, "expected an integer");
    const std::int64_t x = node->as_integer()->get();
    if (x < lo || x > hi) {
      fail(k, "value " + std::to_string(x) + " out of range: allowed [" + std::to_string(lo) + ", " +
                  std::to_string(hi) + "]");
    }
    return x;
  }

  bool boolean(const std::string& k, bool fallback) {
    const toml::node* node = find(k);
    if (node == nullptr) return fallback;
    if (!node->is_boolean()) fail(k, "expected true or false");
    return node->as_boolean()->get();
  }

  // A non-empty string, one of `allowed` when that is given.
  std::string text(const std::string& k, const std::string& fallback,
                   const std::vector<std::string>& allowed = {}) {
    const toml::node* node = find(k);
    if (node == nullptr) return fallback;
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
    return v;
  }

  // An array of numbers: any length when count is nullopt, else exactly count; infinite values only when
  // allow_infinite. Absent gives nullopt.
  std::optional<std::vector<double>> numbers(const std::string& k,
                                             std::optional<std::size_t> count = std::nullopt,
                                             bool allow_infinite = false) {
    const toml::node* node = find(k);
    if (node == nullptr) return std::nullopt;
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
      const double v = as_number(e, k);
      if (std::isnan(v) || (!allow_infinite && !std::isfinite(v))) {
        fail(k, "element " + std::to_string(i) + " is not finite");
      }
      out.push_back(v);
    }
    return out;
  }

  std::vector<double> required_numbers(const std::string& k, std::size_t count, bool allow_infinite = false) {
    auto v = numbers(k, count, allow_infinite);
    if (!v) fail(k, "missing: an array of " + std::to_string(count) + " numbers");
    return *v;
  }

  void finish() const {
    if (table_ == nullptr) return;
    for (const auto& [k, node] : *table_) {
      const std::string name(k.str());
      if (used_.count(name) == 0) {
        std::string list;
        for (const auto& u : used_) list += (list.empty() ? "" : ", ") + u;
        throw InputError(source_ + ": unknown key " + key(name) + " (allowed here: " + list + ")");
      }
    }
  }

 private:
  double as_number(const toml::node& node, const std::string& k) const {
    if (node.is_floating_point()) return node.as_floating_point()->get();
    if (node.is_integer()) return static_cast<double>(node.as_integer()->get());
    fail(k, "expected a number");
  }

  const toml::table* table_;
  std::string name_;
  std::string source_;
  std::set<std::string> used_;
};

}  // namespace craterkit::sph
