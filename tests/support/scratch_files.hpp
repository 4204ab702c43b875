// Files for the tests that read and write them: a fresh folder under the temporary
// directory and a text file written in one call.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

namespace scratch_files {

// An empty folder `mixmesh-<prefix>-<name>` under the temporary directory.
inline std::filesystem::path folder(const std::string& prefix, const std::string& name) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("mixmesh-" + prefix + "-" + name);
  std::filesystem::remove_all(path);
  std::filesystem::create_directories(path);
  return path;
}

// Writes `text` to `path`, creating its folder.
inline void write(const std::filesystem::path& path, const std::string& text) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

}  // namespace scratch_files
