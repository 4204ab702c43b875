#include <glob.h>

#include <cctype>
#include <fstream>

#include "mixmesh/batch/batch.hpp"

namespace mixmesh::batch {

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> expand_pattern(const std::string& pattern) {
  if (pattern.find_first_of("*?[") == std::string::npos) {
    if (!fs::is_regular_file(pattern)) throw Error(pattern + ": no such config file");
    return {pattern};
  }
  glob_t matches{};
  const int status = glob(pattern.c_str(), 0, nullptr, &matches);
  std::vector<fs::path> result;
  if (status == 0)
    for (std::size_t match = 0; match < matches.gl_pathc; ++match)
      result.emplace_back(matches.gl_pathv[match]);
  globfree(&matches);
  if (result.empty()) throw Error(pattern + ": the pattern matches no file");
  return result;
}

bool is_list_file(const fs::path& path) {
  return path.extension() == ".txt" || path.extension() == ".list";
}

}  // namespace

std::vector<fs::path> collect_configs(const std::vector<std::string>& inputs) {
  std::vector<fs::path> configs;
  for (const std::string& input : inputs) {
    if (!is_list_file(input)) {
      for (const fs::path& path : expand_pattern(input)) configs.push_back(path);
      continue;
    }
    std::ifstream list(input);
    if (!list) throw Error(input + ": cannot open list file");
    std::string line;
    long number = 0;
    while (std::getline(list, line)) {
      ++number;
      line = line.substr(0, line.find('#'));
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos) continue;
      const std::string entry = line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
      const fs::path path =
          fs::path(entry).is_absolute() ? fs::path(entry) : fs::path(input).parent_path() / entry;
      try {
        for (const fs::path& match : expand_pattern(path.string())) configs.push_back(match);
      } catch (const Error& error) {
        throw file_error(input, number, error.what());
      }
    }
  }
  return configs;
}

std::vector<BatchCase> expand_sweeps(const fs::path& config, const std::vector<config::Sweep>& sweeps) {
  std::vector<BatchCase> cases{{config.stem().string(), config, {}}};
  for (const config::Sweep& sweep : sweeps) {
    const std::string short_key = sweep.key.substr(sweep.key.rfind('.') + 1);
    std::vector<BatchCase> grown;
    for (const BatchCase& base : cases) {
      for (const std::string& value : sweep.values) {
        BatchCase next = base;
        std::string label;
        for (char character : value)
          if (std::isalnum(static_cast<unsigned char>(character)) || character == '.' || character == '-')
            label += character;
        next.name += "__" + short_key + "-" + label;
        next.settings.push_back(sweep.key + "=" + value);
        grown.push_back(std::move(next));
      }
    }
    cases = std::move(grown);
  }
  return cases;
}

}  // namespace mixmesh::batch
