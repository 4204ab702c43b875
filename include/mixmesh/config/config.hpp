// Config files (TOML, through toml++): typed reading with the position of every
// value, so each error names file:line:column.
//
//   config::Document document = config::Document::load("cases/onera_m6.toml");
//   config::Section wing = document.root().section("wing");
//   WingOptions options;                       // defaults live in the struct
//   wing.read("root_chord", options.root_chord, config::Bounds::positive());
//   wing.read_path("airfoil", options.airfoil); // resolved against the config's folder
//   wing.finish();                             // rejects keys nobody read
//
// Q: why track read keys instead of a schema? A: the option structs are the schema;
// a key no reader asked for is a typo or an option of another version, and is
// reported with its position rather than silently ignored.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mixmesh/core/error.hpp"

namespace mixmesh::config {

// Closed or open bounds on a number; unset sides are unbounded.
struct Bounds {
  std::optional<double> minimum;
  std::optional<double> maximum;
  bool exclusive_minimum = false;
  bool exclusive_maximum = false;

  static Bounds positive() { return {0.0, std::nullopt, true, false}; }
  static Bounds non_negative() { return {0.0, std::nullopt, false, false}; }
  static Bounds at_least(double value) { return {value, std::nullopt, false, false}; }
  static Bounds between(double low, double high) { return {low, high, false, false}; }
  bool contains(double value) const;
  std::string describe() const;  // e.g. "> 0", "in [0, 90]"
};

struct DocumentData;  // the parsed TOML and its source, shared by every Section

class Section {
 public:
  Section(std::shared_ptr<DocumentData> document, const void* table, std::string path);

  bool has(std::string_view key) const;

  // Optional values: the argument keeps its default when the key is absent. A value
  // of the wrong type or out of bounds throws config::Error at the value's position.
  void read(std::string_view key, double& value, const Bounds& bounds = {});
  void read(std::string_view key, int& value, const Bounds& bounds = {});
  void read(std::string_view key, bool& value);
  void read(std::string_view key, std::string& value);
  void read(std::string_view key, std::vector<double>& values, const Bounds& bounds = {});
  void read(std::string_view key, std::vector<std::string>& values);
  // A string that must be one of `choices`.
  void read_choice(std::string_view key, std::string& value, const std::vector<std::string>& choices);
  // The same for an option with named values: `value` keeps its own as the default
  // and takes the value of the name the file gives.
  template <class Value>
  void read_choice(std::string_view key, Value& value,
                   std::initializer_list<std::pair<const char*, Value>> choices) {
    std::string name;
    std::vector<std::string> names;
    for (const auto& [choice, meaning] : choices) {
      names.emplace_back(choice);
      if (meaning == value) name = choice;
    }
    read_choice(key, name, names);
    for (const auto& [choice, meaning] : choices)
      if (name == choice) value = meaning;
  }
  // A path, resolved relative to the folder of the config file.
  void read_path(std::string_view key, std::filesystem::path& value);

  // Required variants: a missing key is an error naming the section.
  void require(std::string_view key, double& value, const Bounds& bounds = {});
  void require(std::string_view key, std::string& value);

  // Sub-tables: [wing.planform] or wing = { ... }.
  Section section(std::string_view key);  // required
  std::optional<Section> optional_section(std::string_view key);
  // Arrays of tables: [[station]] entries in order.
  std::vector<Section> sections(std::string_view key);

  // Throws on the first key of this table that no read/section call asked for.
  void finish() const;

  // An error located at `key` (or at the table when key is empty).
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  // "file:line:column" of `key` (of the table when key is empty or absent).
  std::string where(std::string_view key = {}) const;
  // Dotted name of the table, e.g. "wing.planform" ("" for the root).
  const std::string& path() const { return path_; }

 private:
  const void* find(std::string_view key);
  const void* find_scalar(std::string_view key);  // records sweeps, see Document
  std::shared_ptr<DocumentData> document_;
  const void* table_;
  std::string path_;
  std::vector<std::string> used_;
  bool in_array_ = false;  // inside an array of tables, where a batch sweep cannot reach
};

// A batch sweep: a scalar option given as an array of values, one run per value.
struct Sweep {
  std::string key;                  // dotted, e.g. "planform.leading_edge_sweep"
  std::vector<std::string> values;  // each in TOML syntax, ready for Document::set
};

class Document {
 public:
  // Parse errors are reported as "file:line:column: message".
  static Document load(const std::filesystem::path& file);
  static Document parse(std::string_view text, const std::filesystem::path& source_name);

  Section root() const;
  const std::filesystem::path& file() const;
  // Folder that relative paths in the file are resolved against.
  std::filesystem::path folder() const;

  // Sets the value at a dotted key from "key=value" (value in TOML syntax, e.g.
  // planform.taper=0.3 or output.formats=["vtu"]); missing tables are created.
  void set(std::string_view assignment);

  // From now on, a scalar read that meets an array records a Sweep and reads the
  // array's first element, so one pass of the option readers lists the sweeps.
  void discover_sweeps();
  const std::vector<Sweep>& sweeps() const;

 private:
  std::shared_ptr<DocumentData> data_;
};

}  // namespace mixmesh::config
