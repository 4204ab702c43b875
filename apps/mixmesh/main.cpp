#include <exception>
#include <iostream>

#include "commands.hpp"
#include "mixmesh/core/error.hpp"

int main(int argument_count, char** arguments) {
  CLI::App application{
      "mixmesh: mixed hexahedral/prismatic/pyramidal/tetrahedral meshes for aircraft CFD.\n"
      "Run 'mixmesh COMMAND --help' for the options of one command."};
  application.require_subcommand(1);
  application.set_version_flag("--version", "mixmesh 0.1.0");
  // One line per subcommand (commands.hpp).
  mixmesh::cli::add_batch_command(application);
  mixmesh::cli::add_generate_command(application);
  mixmesh::cli::add_convert_command(application);
  mixmesh::cli::add_check_command(application);
  mixmesh::cli::add_surface_command(application);
  mixmesh::cli::add_deform_command(application);
  mixmesh::cli::add_march_command(application);
  mixmesh::cli::add_compare_command(application);

  try {
    application.parse(argument_count, arguments);
  } catch (const CLI::ParseError& error) {
    return application.exit(error);
  } catch (const mixmesh::Error& error) {
    std::cerr << "mixmesh: error: " << error.what() << '\n';
    return 1;
  } catch (const std::exception& error) {
    std::cerr << "mixmesh: internal error: " << error.what() << '\n';
    return 3;
  }
  return 0;
}
