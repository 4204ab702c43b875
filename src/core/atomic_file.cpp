#include "mixmesh/core/atomic_file.hpp"

#include <fstream>
#include <random>
#include <string>

#include "mixmesh/core/error.hpp"

namespace mixmesh {

namespace fs = std::filesystem;

void write_atomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  std::random_device entropy;
  const fs::path temporary = path.parent_path() / (".tmp-" + std::to_string(entropy() % 1000000000u) + "-" +
                                                   path.filename().string());
  try {
    write(temporary);
    std::error_code code;
    fs::rename(temporary, path, code);
    if (code) throw Error(path.string() + ": cannot write: " + code.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

void write_text_atomically(const fs::path& path, const std::string& text) {
  write_atomically(path, [&](const fs::path& temporary) {
    std::ofstream file(temporary);
    file << text;
    if (!file.flush()) throw Error(path.string() + ": cannot write");
  });
}

}  // namespace mixmesh
