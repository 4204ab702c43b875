// The subcommands of the mixmesh program. Each file NAME_command.cpp adds one
// subcommand to the application; errors leave as mixmesh::Error and main() turns
// them into one line on stderr and a non-zero exit.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>

namespace mixmesh::cli {

// add_NAME_command declarations go here, one per subcommand.
void add_batch_command(CLI::App& application);
void add_generate_command(CLI::App& application);
void add_convert_command(CLI::App& application);
void add_check_command(CLI::App& application);
void add_surface_command(CLI::App& application);
void add_deform_command(CLI::App& application);
void add_march_command(CLI::App& application);
void add_compare_command(CLI::App& application);

// Where --keep-invalid writes a mesh that failed its checks, for inspection: the output
// with "invalid" before its extension (wing.vtu -> wing.invalid.vtu).
inline std::filesystem::path kept_invalid_path(const std::filesystem::path& output) {
  return output.parent_path() / (output.stem().string() + ".invalid" + output.extension().string());
}

}  // namespace mixmesh::cli
