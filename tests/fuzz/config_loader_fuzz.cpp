// libFuzzer target: the config loader must turn any input into either options or
// one mixmesh::Error, never a crash, hang or other exception.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mixmesh/config/config.hpp"

namespace {

// Reads the tables and arrays of tables the way option readers do, to walk every
// branch of Section on arbitrary documents.
void read_everything(mixmesh::config::Section section, int depth) {
  double number = 1.0;
  int integer = 1;
  bool flag = false;
  std::string text;
  std::vector<double> numbers;
  std::vector<std::string> words;
  std::filesystem::path path;
  section.read("number", number, mixmesh::config::Bounds::positive());
  section.read("integer", integer, mixmesh::config::Bounds::between(0, 100));
  section.read("flag", flag);
  section.read("text", text);
  section.read("numbers", numbers);
  section.read("words", words);
  section.read_path("path", path);
  std::string choice = "a";
  section.read_choice("choice", choice, {"a", "b"});
  if (depth < 4) {
    if (auto child = section.optional_section("child")) read_everything(*child, depth + 1);
    for (auto& entry : section.sections("entry")) read_everything(entry, depth + 1);
  }
  section.finish();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto document = mixmesh::config::Document::parse(text, "fuzz.toml");
    read_everything(document.root(), 0);
  } catch (const mixmesh::Error&) {
  }
  return 0;
}
