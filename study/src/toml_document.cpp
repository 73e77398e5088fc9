#include "craterkit/study/toml_document.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "craterkit/common/input_error.hpp"
#include "toml_emit.hpp"

namespace craterkit::study {

namespace detail {

namespace {

bool is_bare_key(std::string_view key) {
  if (key.empty()) return false;
  for (const char c : key) {
    const bool ok =
        (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

bool is_array_of_tables(const toml::node& node) {
  const auto* array = node.as_array();
  if (array == nullptr || array->empty()) return false;
  for (const auto& element : *array) {
    if (!element.is_table()) return false;
  }
  return true;
}

std::string join_path(const std::string& path, std::string_view key) {
  return path.empty() ? toml_key(key) : path + "." + toml_key(key);
}

}  // namespace

std::string toml_key(std::string_view key) {
  return is_bare_key(key) ? std::string(key) : toml_string(key);
}

std::string toml_literal(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return toml_string(node.as_string()->get());
    case toml::node_type::integer:
      return std::to_string(node.as_integer()->get());
    case toml::node_type::floating_point:
      return toml_float(node.as_floating_point()->get());
    case toml::node_type::boolean:
      return node.as_boolean()->get() ? "true" : "false";
    case toml::node_type::date: {
      std::ostringstream out;
      out << *node.as_date();
      return out.str();
    }
    case toml::node_type::time: {
      std::ostringstream out;
      out << *node.as_time();
      return out.str();
    }
    case toml::node_type::date_time: {
      std::ostringstream out;
      out << *node.as_date_time();
      return out.str();
    }
    case toml::node_type::array: {
      std::string out = "[";
      bool first = true;
      for (const auto& element : *node.as_array()) {
        out += (first ? "" : ", ") + toml_literal(element);
        first = false;
      }
      return out + "]";
    }
    case toml::node_type::table: {
      const auto& table = *node.as_table();
      if (table.empty()) return "{}";
      std::string out = "{ ";
      bool first = true;
      for (const auto& [key, value] : table) {
        out += (first ? "" : ", ") + toml_key(key.str()) + " = " + toml_literal(value);
        first = false;
      }
      return out + " }";
    }
    case toml::node_type::none:
      break;
  }
  return "";
}

void dump_table(std::string& out, const toml::table& table, const std::string& path) {
  for (const auto& [key, value] : table) {
    if (value.is_table() || is_array_of_tables(value)) continue;
    out += toml_key(key.str()) + " = " + toml_literal(value) + "\n";
  }
  for (const auto& [key, value] : table) {
    if (!value.is_table()) continue;
    const std::string name = join_path(path, key.str());
    out += "\n[" + name + "]\n";
    dump_table(out, *value.as_table(), name);
  }
  for (const auto& [key, value] : table) {
    if (!is_array_of_tables(value)) continue;
    const std::string name = join_path(path, key.str());
    for (const auto& element : *value.as_array()) {
      out += "\n[[" + name + "]]\n";
      dump_table(out, *element.as_table(), name);
    }
  }
}

toml::table parse_literal(std::string_view text, const std::string& what) {
  try {
    toml::table parsed = toml::parse("v = " + std::string(text) + "\n");
    if (parsed.size() != 1 || !parsed.contains("v")) {
      throw InputError(what + ": '" + std::string(text) + "' is not one TOML value");
    }
    return parsed;
  } catch (const toml::parse_error& e) {
    throw InputError(what + ": '" + std::string(text) + "' is not a TOML value (" +
                     std::string(e.description()) + ")");
  }
}

}  // namespace detail

std::vector<std::string> split_dotted(std::string_view dotted) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto dot = dotted.find('.', start);
    const auto part =
        dotted.substr(start, dot == std::string_view::npos ? std::string_view::npos : dot - start);
    if (part.empty()) throw InputError("key '" + std::string(dotted) + "': empty part in a dotted key");
    parts.emplace_back(part);
    if (dot == std::string_view::npos) break;
    start = dot + 1;
  }
  return parts;
}

std::string toml_float(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  std::string text(buffer, result.ptr);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

std::string toml_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          char code[8];
          std::snprintf(code, sizeof(code), "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
          out += code;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

struct TomlDocument::Impl {
  toml::table root;
  std::string source;
};

namespace {

// The table holding the last part of `parts`, or null when a part on the way is absent or not a table.
const toml::table* parent_table(const toml::table& root, const std::vector<std::string>& parts) {
  const toml::table* table = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const toml::node* next = table->get(parts[i]);
    if (next == nullptr || !next->is_table()) return nullptr;
    table = next->as_table();
  }
  return table;
}

const toml::node* find_node(const toml::table& root, std::string_view dotted) {
  const auto parts = split_dotted(dotted);
  const toml::table* table = parent_table(root, parts);
  return table == nullptr ? nullptr : table->get(parts.back());
}

}  // namespace

TomlDocument::TomlDocument(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
TomlDocument::TomlDocument(const TomlDocument& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
TomlDocument& TomlDocument::operator=(const TomlDocument& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
TomlDocument::TomlDocument(TomlDocument&&) noexcept = default;
TomlDocument& TomlDocument::operator=(TomlDocument&&) noexcept = default;
TomlDocument::~TomlDocument() = default;

TomlDocument TomlDocument::parse(const std::string& text, const std::string& source) {
  auto impl = std::make_unique<Impl>();
  impl->source = source;
  try {
    impl->root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream message;
    message << source << ":" << e.source().begin.line << ":" << e.source().begin.column
            << ": TOML syntax error: " << e.description();
    throw InputError(message.str());
  }
  return TomlDocument(std::move(impl));
}

TomlDocument TomlDocument::parse_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot be read (missing or not a file)");
  std::ostringstream text;
  text << in.rdbuf();
  return parse(text.str(), file.string());
}

const std::string& TomlDocument::source() const {
  return impl_->source;
}

bool TomlDocument::contains(std::string_view dotted) const {
  return find_node(impl_->root, dotted) != nullptr;
}

std::optional<std::string> TomlDocument::literal(std::string_view dotted) const {
  const toml::node* node = find_node(impl_->root, dotted);
  if (node == nullptr || node->is_table()) return std::nullopt;
  return detail::toml_literal(*node);
}

std::optional<double> TomlDocument::number(std::string_view dotted) const {
  const toml::node* node = find_node(impl_->root, dotted);
  if (node == nullptr) return std::nullopt;
  if (node->is_floating_point()) return node->as_floating_point()->get();
  if (node->is_integer()) return static_cast<double>(node->as_integer()->get());
  throw InputError(impl_->source + ": " + std::string(dotted) + ": expected a number, got " +
                   detail::toml_literal(*node));
}

std::optional<std::string> TomlDocument::text(std::string_view dotted) const {
  const toml::node* node = find_node(impl_->root, dotted);
  if (node == nullptr) return std::nullopt;
  if (!node->is_string()) {
    throw InputError(impl_->source + ": " + std::string(dotted) + ": expected a string, got " +
                     detail::toml_literal(*node));
  }
  return node->as_string()->get();
}

std::optional<std::vector<double>> TomlDocument::numbers(std::string_view dotted) const {
  const toml::node* node = find_node(impl_->root, dotted);
  if (node == nullptr) return std::nullopt;
  std::vector<double> out;
  if (const auto* array = node->as_array()) {
    for (const auto& element : *array) {
      if (element.is_floating_point()) {
        out.push_back(element.as_floating_point()->get());
      } else if (element.is_integer()) {
        out.push_back(static_cast<double>(element.as_integer()->get()));
      } else {
        array = nullptr;
        break;
      }
    }
    if (array != nullptr) return out;
  }
  throw InputError(impl_->source + ": " + std::string(dotted) + ": expected an array of numbers, got " +
                   detail::toml_literal(*node));
}

bool TomlDocument::is_table(std::string_view dotted) const {
  const toml::node* node = find_node(impl_->root, dotted);
  return node != nullptr && node->is_table();
}

void TomlDocument::set(std::string_view dotted, std::string_view toml_value) {
  const auto parts = split_dotted(dotted);
  toml::table parsed = detail::parse_literal(toml_value, impl_->source + ": " + std::string(dotted));
  toml::table* table = &impl_->root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    toml::node* next = table->get(parts[i]);
    if (next == nullptr) {
      table->insert_or_assign(parts[i], toml::table{});
      next = table->get(parts[i]);
    }
    if (!next->is_table()) {
      throw InputError(impl_->source + ": " + std::string(dotted) + ": '" + parts[i] +
                       "' is a value, not a table, in this document");
    }
    table = next->as_table();
  }
  parsed.get("v")->visit([&](auto&& value) { table->insert_or_assign(parts.back(), std::move(value)); });
}

void TomlDocument::set_number(std::string_view dotted, double value) {
  set(dotted, toml_float(value));
}

void TomlDocument::set_text(std::string_view dotted, const std::string& value) {
  set(dotted, toml_string(value));
}

bool TomlDocument::erase(std::string_view dotted) {
  const auto parts = split_dotted(dotted);
  auto* table = const_cast<toml::table*>(parent_table(impl_->root, parts));
  return table != nullptr && table->erase(parts.back()) > 0;
}

std::string TomlDocument::dump() const {
  std::string out;
  detail::dump_table(out, impl_->root, "");
  return out;
}

}  // namespace craterkit::study
