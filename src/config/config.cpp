#include "mixmesh/config/config.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <toml++/toml.h>

namespace mixmesh::config {

struct DocumentData {
  toml::table root;
  std::filesystem::path file;
  bool discover_sweeps = false;
  std::vector<Sweep> sweeps;
};

namespace {

std::string qualified(const std::string& section, std::string_view key) {
  return section.empty() ? std::string(key) : section + "." + std::string(key);
}

const toml::table& as_table(const void* table) {
  return *static_cast<const toml::table*>(table);
}

std::string position(const std::filesystem::path& file, const toml::source_region& source) {
  if (source.begin.line == 0) return file.string() + " (value set on the command line)";
  return file.string() + ":" + std::to_string(source.begin.line) + ":" + std::to_string(source.begin.column);
}

std::string format_number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// The shortest decimal text that reads back as exactly `value`.
std::string shortest_text(double value) {
  char text[40];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date or time";
  }
}

}  // namespace

bool Bounds::contains(double value) const {
  if (!std::isfinite(value)) return false;
  if (minimum && (exclusive_minimum ? value <= *minimum : value < *minimum)) return false;
  if (maximum && (exclusive_maximum ? value >= *maximum : value > *maximum)) return false;
  return true;
}

std::string Bounds::describe() const {
  if (minimum && maximum)
    return std::string("in ") + (exclusive_minimum ? "(" : "[") + format_number(*minimum) + ", " +
           format_number(*maximum) + (exclusive_maximum ? ")" : "]");
  if (minimum) return std::string(exclusive_minimum ? "> " : ">= ") + format_number(*minimum);
  if (maximum) return std::string(exclusive_maximum ? "< " : "<= ") + format_number(*maximum);
  return "finite";
}

Section::Section(std::shared_ptr<DocumentData> document, const void* table, std::string path)
    : document_(std::move(document)), table_(table), path_(std::move(path)) {}

bool Section::has(std::string_view key) const {
  return as_table(table_).contains(key);
}

const void* Section::find(std::string_view key) {
  const toml::node* node = as_table(table_).get(key);
  if (node != nullptr) used_.emplace_back(key);
  return node;
}

const void* Section::find_scalar(std::string_view key) {
  const auto* node = static_cast<const toml::node*>(find(key));
  if (node == nullptr || !node->is_array() || !document_->discover_sweeps) return node;
  const toml::array& values = *node->as_array();
  const bool scalars =
      !values.empty() && std::all_of(values.begin(), values.end(), [&](const toml::node& value) {
        return value.is_number() ? values.front().is_number() : value.type() == values.front().type();
      });
  if (!scalars || values.front().is_array() || values.front().is_table()) return node;
  // `--set` names a key by its dotted path, which does not say which entry of an array
  // of tables it means.
  if (in_array_)
    fail(key,
         "'" + qualified(path_, key) +
             "' is inside an array of tables ([[...]]): a batch sweep (a list of values) cannot vary it");
  Sweep sweep{qualified(path_, key), {}};
  for (const toml::node& value : values) {
    // Floating-point values in their shortest round-trip form (0.3, not 0.2999…),
    // so the case names stay readable.
    sweep.values.push_back(value.is_floating_point() ? shortest_text(value.as_floating_point()->get()) : [&] {
      std::ostringstream text;
      value.visit([&](const auto& scalar) { text << scalar; });
      return text.str();
    }());
  }
  const auto known = std::find_if(document_->sweeps.begin(), document_->sweeps.end(),
                                  [&](const Sweep& other) { return other.key == sweep.key; });
  if (known == document_->sweeps.end()) document_->sweeps.push_back(std::move(sweep));
  return &values.front();
}

std::string Section::where(std::string_view key) const {
  const toml::node* node = key.empty() ? nullptr : as_table(table_).get(key);
  return position(document_->file, node != nullptr ? node->source() : as_table(table_).source());
}

void Section::fail(std::string_view key, const std::string& message) const {
  throw Error(where(key) + ": " + message);
}

namespace {

double number_value(const Section& section, std::string_view key, const toml::node& node,
                    const Bounds& bounds) {
  std::optional<double> value;
  if (node.is_floating_point()) value = node.as_floating_point()->get();
  if (node.is_integer()) value = static_cast<double>(node.as_integer()->get());
  if (!value)
    section.fail(key, "'" + qualified(section.path(), key) + "' must be a number, not " + type_name(node));
  if (!bounds.contains(*value))
    section.fail(key, "'" + qualified(section.path(), key) + "' = " + format_number(*value) + " must be " +
                          bounds.describe());
  return *value;
}

}  // namespace

void Section::read(std::string_view key, double& value, const Bounds& bounds) {
  if (const auto* node = static_cast<const toml::node*>(find_scalar(key)))
    value = number_value(*this, key, *node, bounds);
}

void Section::read(std::string_view key, int& value, const Bounds& bounds) {
  const auto* node = static_cast<const toml::node*>(find_scalar(key));
  if (node == nullptr) return;
  if (!node->is_integer())
    fail(key, "'" + qualified(path_, key) + "' must be an integer, not " + type_name(*node));
  const auto integer = node->as_integer()->get();
  if (integer < -2147483647 || integer > 2147483647 || !bounds.contains(static_cast<double>(integer)))
    fail(key, "'" + qualified(path_, key) + "' = " + std::to_string(integer) + " must be " +
                  (bounds.contains(static_cast<double>(integer)) ? std::string("a 32-bit integer")
                                                                 : bounds.describe()));
  value = static_cast<int>(integer);
}

void Section::read(std::string_view key, bool& value) {
  const auto* node = static_cast<const toml::node*>(find_scalar(key));
  if (node == nullptr) return;
  if (!node->is_boolean())
    fail(key, "'" + qualified(path_, key) + "' must be true or false, not " + type_name(*node));
  value = node->as_boolean()->get();
}

void Section::read(std::string_view key, std::string& value) {
  const auto* node = static_cast<const toml::node*>(find_scalar(key));
  if (node == nullptr) return;
  if (!node->is_string())
    fail(key, "'" + qualified(path_, key) + "' must be a string, not " + type_name(*node));
  value = node->as_string()->get();
}

void Section::read(std::string_view key, std::vector<double>& values, const Bounds& bounds) {
  const auto* node = static_cast<const toml::node*>(find(key));
  if (node == nullptr) return;
  if (!node->is_array())
    fail(key, "'" + qualified(path_, key) + "' must be an array of numbers, not " + type_name(*node));
  std::vector<double> result;
  for (const toml::node& element : *node->as_array()) {
    if (!element.is_number())
      throw Error(position(document_->file, element.source()) + ": '" + qualified(path_, key) +
                  "' must hold numbers only, not " + type_name(element));
    const double number = element.value<double>().value_or(0.0);
    if (!bounds.contains(number))
      throw Error(position(document_->file, element.source()) + ": '" + qualified(path_, key) + "' holds " +
                  format_number(number) + ", which must be " + bounds.describe());
    result.push_back(number);
  }
  values = std::move(result);
}

void Section::read(std::string_view key, std::vector<std::string>& values) {
  const auto* node = static_cast<const toml::node*>(find(key));
  if (node == nullptr) return;
  if (!node->is_array())
    fail(key, "'" + qualified(path_, key) + "' must be an array of strings, not " + type_name(*node));
  std::vector<std::string> result;
  for (const toml::node& element : *node->as_array()) {
    if (!element.is_string())
      throw Error(position(document_->file, element.source()) + ": '" + qualified(path_, key) +
                  "' must hold strings only, not " + type_name(element));
    result.push_back(element.as_string()->get());
  }
  values = std::move(result);
}

void Section::read_choice(std::string_view key, std::string& value, const std::vector<std::string>& choices) {
  std::string chosen = value;
  read(key, chosen);
  for (const std::string& choice : choices) {
    if (choice == chosen) {
      value = chosen;
      return;
    }
  }
  std::string list;
  for (const std::string& choice : choices) list += (list.empty() ? "" : ", ") + choice;
  fail(key, "'" + qualified(path_, key) + "' = \"" + chosen + "\" must be one of: " + list);
}

void Section::read_path(std::string_view key, std::filesystem::path& value) {
  std::string text;
  if (!has(key)) return;
  read(key, text);
  if (text.empty()) fail(key, "'" + qualified(path_, key) + "' must not be empty");
  const std::filesystem::path path(text);
  value = path.is_absolute() ? path : document_->file.parent_path() / path;
}

void Section::require(std::string_view key, double& value, const Bounds& bounds) {
  if (!has(key)) fail({}, "[" + path_ + "] needs '" + std::string(key) + "'");
  read(key, value, bounds);
}

void Section::require(std::string_view key, std::string& value) {
  if (!has(key)) fail({}, "[" + path_ + "] needs '" + std::string(key) + "'");
  read(key, value);
}

Section Section::section(std::string_view key) {
  std::optional<Section> found = optional_section(key);
  if (!found) fail({}, "missing table [" + qualified(path_, key) + "]");
  return *found;
}

std::optional<Section> Section::optional_section(std::string_view key) {
  const auto* node = static_cast<const toml::node*>(find(key));
  if (node == nullptr) return std::nullopt;
  if (!node->is_table())
    fail(key, "'" + qualified(path_, key) + "' must be a table, not " + type_name(*node));
  Section child(document_, node->as_table(), qualified(path_, key));
  child.in_array_ = in_array_;
  return child;
}

std::vector<Section> Section::sections(std::string_view key) {
  std::vector<Section> result;
  const auto* node = static_cast<const toml::node*>(find(key));
  if (node == nullptr) return result;
  if (!node->is_array_of_tables())
    fail(key,
         "'" + qualified(path_, key) + "' must be an array of tables ([[" + qualified(path_, key) + "]])");
  for (const toml::node& element : *node->as_array()) {
    result.emplace_back(document_, element.as_table(), qualified(path_, key));
    result.back().in_array_ = true;
  }
  return result;
}

void Section::finish() const {
  for (const auto& [key, node] : as_table(table_)) {
    if (std::find(used_.begin(), used_.end(), key.str()) != used_.end()) continue;
    throw Error(position(document_->file, key.source()) + ": unknown key '" + qualified(path_, key.str()) +
                "'");
  }
}

Document Document::load(const std::filesystem::path& file) {
  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw Error(file.string() + ": cannot open config file");
  std::ostringstream text;
  text << stream.rdbuf();
  if (stream.bad()) throw Error(file.string() + ": cannot read config file");
  return parse(text.str(), file);
}

Document Document::parse(std::string_view text, const std::filesystem::path& source_name) {
  Document document;
  document.data_ = std::make_shared<DocumentData>();
  document.data_->file = source_name;
  try {
    document.data_->root = toml::parse(text, source_name.string());
  } catch (const toml::parse_error& error) {
    throw Error(position(source_name, error.source()) + ": " + std::string(error.description()));
  }
  return document;
}

void Document::set(std::string_view assignment) {
  const std::size_t equals = assignment.find('=');
  const std::string key(assignment.substr(0, equals));
  if (equals == std::string_view::npos || key.empty())
    throw Error("--set " + std::string(assignment) + ": expected KEY=VALUE, e.g. planform.taper=0.3");
  toml::table parsed;
  try {
    parsed = toml::parse("value = " + std::string(assignment.substr(equals + 1)), "--set " + key);
  } catch (const toml::parse_error& error) {
    throw Error("--set " + std::string(assignment) + ": " + std::string(error.description()));
  }
  toml::table* table = &data_->root;
  std::size_t start = 0;
  for (std::size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', start)) {
    const std::string part = key.substr(start, dot - start);
    toml::node* child = table->get(part);
    if (child == nullptr) child = &table->insert_or_assign(part, toml::table{}).first->second;
    if (!child->is_table())
      throw Error("--set " + std::string(assignment) + ": '" + key.substr(0, dot) + "' is not a table");
    table = child->as_table();
    start = dot + 1;
  }
  const std::string leaf = key.substr(start);
  parsed.get("value")->visit([&](const auto& value) { table->insert_or_assign(leaf, value); });
}

void Document::discover_sweeps() {
  data_->discover_sweeps = true;
}
const std::vector<Sweep>& Document::sweeps() const {
  return data_->sweeps;
}

Section Document::root() const {
  return Section(data_, &data_->root, "");
}
const std::filesystem::path& Document::file() const {
  return data_->file;
}
std::filesystem::path Document::folder() const {
  return data_->file.parent_path();
}

}  // namespace mixmesh::config
