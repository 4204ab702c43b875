// Atomic output: a file is written under a temporary name beside its destination
// and renamed when complete, so a failed run never leaves a truncated file where a
// good one was (rename is atomic within one file system).
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace mixmesh {

// Calls write(temporary_path); on success renames the temporary file to path, on any
// exception removes it and rethrows. The temporary keeps the destination's
// extension, so writers that choose their format by extension still work.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path&)>& write);

// Writes `text` as the whole of path, atomically; throws mixmesh::Error naming path.
void write_text_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace mixmesh
