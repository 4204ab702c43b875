// The Python picture scripts (scripts/plot-*.py) that `check --hist` and `compare`
// run, and how they are found and started.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace mixmesh::cli {

// The folder holding `script`: `given` (a command option) if set, then
// $MIXMESH_SCRIPTS, share/mixmesh/scripts of an installation beside the program, then
// scripts/ of the program's parent folders (a build tree inside the source tree).
// Empty when none holds it.
std::filesystem::path find_plot_scripts(const std::string& script, const std::string& given = {});

// Runs `command` (program first, searched in PATH) without a shell and waits;
// throws mixmesh::Error naming the program and its exit status when it fails.
void run_plot_script(const std::vector<std::string>& command);

}  // namespace mixmesh::cli
