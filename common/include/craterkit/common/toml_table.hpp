#pragma once
// The one reader of TOML input (configurations, material, body, population and constant-set files).
// A TomlTable is one table of a parsed document. Its typed getters check type and range and remember the
// keys they were asked for; finish() then rejects every key that was not read (unknown or misspelt),
// naming it and listing the allowed ones. Every error is a craterkit::InputError
// "<source>: <table>.<key>: <what>", so a user sees the file, the key, the value and what is allowed.
// toml++ stays behind this interface (common/src/toml_table.cpp).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace craterkit {

class TomlTable {
 public:
  // Parses TOML text; `source` names it in messages. A syntax error is an InputError
  // "<source>:<line>:<column>: TOML syntax error: <what>".
  static TomlTable parse(const std::string& text, const std::string& source);
  // Reads and parses a file; a missing or unreadable file is an InputError naming it.
  static TomlTable parse_file(const std::filesystem::path& file);

  // The dotted name of key k in this table ("impact.boulders[0].radius"), for messages.
  [[nodiscard]] std::string key(std::string_view k) const;
  [[nodiscard]] const std::string& source() const { return source_; }
  [[nodiscard]] const std::string& name() const { return name_; }
  [[noreturn]] void fail(std::string_view k, const std::string& what) const;

  // Whether the key is present (does not count as read).
  [[nodiscard]] bool contains(std::string_view k) const;
  // The keys present, sorted by name.
  [[nodiscard]] std::vector<std::string> keys() const;
  // Marks a key as read without reading it (its value is checked elsewhere, or deliberately ignored).
  void accept(std::string_view k) { used_.insert(std::string(k)); }

  // A finite number in [lo, hi] (lower bound open when lo_open, upper when hi_open); integers are accepted.
  double number(std::string_view k, double fallback, double lo, double hi, bool lo_open = false,
                bool hi_open = false);
  std::optional<double> optional_number(std::string_view k, double lo, double hi, bool lo_open = false,
                                        bool hi_open = false);
  double required_number(std::string_view k, double lo, double hi, bool lo_open = false,
                         bool hi_open = false);
  // Reports a number that a getter accepted but a check among several keys rejects, in the getters'
  // words: "value <v> out of range: allowed <allowed>" (allowed: "> E_iv = 4720000").
  [[noreturn]] void out_of_range(std::string_view k, double value, const std::string& allowed) const;
  std::int64_t integer(std::string_view k, std::int64_t fallback, std::int64_t lo, std::int64_t hi);
  bool boolean(std::string_view k, bool fallback);
  // A non-empty string, one of `allowed` when that is given.
  std::string text(std::string_view k, const std::string& fallback,
                   const std::vector<std::string>& allowed = {});
  std::optional<std::string> optional_text(std::string_view k, const std::vector<std::string>& allowed = {});
  std::string required_text(std::string_view k, const std::string& what,
                            const std::vector<std::string>& allowed = {});
  // An array of numbers: any length when count is nullopt, else exactly count; infinite values only when
  // allow_infinite. Absent gives nullopt.
  std::optional<std::vector<double>> numbers(std::string_view k,
                                             std::optional<std::size_t> count = std::nullopt,
                                             bool allow_infinite = false);
  std::vector<double> required_numbers(std::string_view k, std::optional<std::size_t> count = std::nullopt,
                                       bool allow_infinite = false);
  // An array of non-empty strings. Absent gives nullopt.
  std::optional<std::vector<std::string>> texts(std::string_view k);

  // The sub-table under key k; an absent key gives an empty table (whose getters return their fallbacks);
  // a value that is not a table is an error.
  TomlTable table(std::string_view k);
  // The sub-table under key k; an absent key is an error.
  TomlTable required_table(std::string_view k);
  [[nodiscard]] bool is_table(std::string_view k) const;
  // An array of tables ([[k]]); absent gives an empty vector.
  std::vector<TomlTable> tables(std::string_view k);

  // Every value the getters of this document (all its tables) returned, defaults included, as sorted lines
  // "<dotted key> = <value>" (numbers with 17 digits, texts quoted, "(absent)" for an optional key not
  // given): two documents read alike give the same text exactly when their readers saw the same values.
  [[nodiscard]] std::string values_read() const;

  // Rejects every key that no getter (or accept()) asked for.
  void finish() const;
  // Rejects now every key not in `allowed`, in finish()'s words. A reader that calls this before its
  // getters reports a misspelt key as unknown (listing the allowed ones) rather than the key it was meant
  // to be as missing. It counts nothing as read: finish() still rejects what no getter asked for.
  void reject_unknown(const std::vector<std::string>& allowed) const;

 private:
  struct Document;
  TomlTable(std::shared_ptr<const Document> document, const void* table, std::string name,
            std::string source);
  [[nodiscard]] const void* find(std::string_view k) const;
  const void* use(std::string_view k);
  void record(std::string_view k, std::string value) const;

  std::shared_ptr<const Document> document_;  // keeps the parsed document alive for sub-tables
  const void* table_ = nullptr;               // the toml++ table, or null for an absent table
  std::string name_;
  std::string source_;
  std::set<std::string> used_;
};

}  // namespace craterkit
