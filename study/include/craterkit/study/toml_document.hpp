#pragma once
// A TOML document edited by dotted key and written back as TOML text: the base configuration and the target
// material of a study's runs are copied, changed and written into each run's folder (study_plan.hpp).
// toml++ stays behind this interface (study/src/toml_document.cpp).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace craterkit::study {

class TomlDocument {
 public:
  // Parses TOML text; a syntax error is an InputError "<source>:<line>:<column>: TOML syntax error: ...".
  static TomlDocument parse(const std::string& text, const std::string& source);
  // Reads and parses a file; a missing file is an InputError naming it.
  static TomlDocument parse_file(const std::filesystem::path& file);

  TomlDocument(const TomlDocument& other);
  TomlDocument& operator=(const TomlDocument& other);
  TomlDocument(TomlDocument&&) noexcept;
  TomlDocument& operator=(TomlDocument&&) noexcept;
  ~TomlDocument();

  [[nodiscard]] const std::string& source() const;
  [[nodiscard]] bool contains(std::string_view dotted) const;
  // The value at a dotted key ("impact.grading") as TOML text ("0.1", "\"quarter\"", "[0.0, 0.0, -1.0]");
  // nullopt when absent. A table is not a value (nullopt).
  [[nodiscard]] std::optional<std::string> literal(std::string_view dotted) const;
  // Typed reads; nullopt when absent, an InputError naming source and key when of another type.
  [[nodiscard]] std::optional<double> number(std::string_view dotted) const;
  [[nodiscard]] std::optional<std::string> text(std::string_view dotted) const;
  [[nodiscard]] std::optional<std::vector<double>> numbers(std::string_view dotted) const;
  [[nodiscard]] bool is_table(std::string_view dotted) const;

  // Sets the key to a TOML value given as text, creating missing tables on the way. InputError when the
  // text is not one TOML value or a part of the path is a value rather than a table.
  void set(std::string_view dotted, std::string_view toml_value);
  void set_number(std::string_view dotted, double value);
  void set_text(std::string_view dotted, const std::string& value);
  // Removes the key; false if it was absent.
  bool erase(std::string_view dotted);

  // TOML text: per table its values first, then its sub-tables and arrays of tables, keys sorted; floats in
  // the shortest form that reads back as the same double. Equal documents give equal text (comments of the
  // source are not kept).
  [[nodiscard]] std::string dump() const;

 private:
  struct Impl;
  explicit TomlDocument(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// "impact.grading" -> {"impact", "grading"}; an empty part is an InputError.
std::vector<std::string> split_dotted(std::string_view dotted);
// A float as TOML, shortest round trip, always with a '.' or an exponent: 2 -> "2.0", 0.05 -> "0.05",
// 1e-5 -> "1e-05", inf -> "inf".
std::string toml_float(double value);
// A TOML basic string with its quotes and escapes.
std::string toml_string(std::string_view text);

}  // namespace craterkit::study
