// Reads the [wing] table (wing_options.hpp).
#include "mixmesh/pipeline/wing_options.hpp"

#include <cmath>

#include "mixmesh/core/error.hpp"

namespace mixmesh {
namespace {

const std::vector<std::string> classic_keys = {"root_chord",          "semi_span", "leading_edge_sweep",
                                               "trailing_edge_sweep", "taper",     "root_twist",
                                               "tip_twist",           "dihedral"};

// The section of a table: airfoil_file or naca (exactly one when `required`).
// Returns false when neither is given and it is not required.
bool read_airfoil(config::Section& table, const NacaOptions& naca, bool required, Airfoil& airfoil) {
  const bool has_file = table.has("airfoil_file");
  const bool has_naca = table.has("naca");
  if (has_file && has_naca) table.fail("naca", "give either 'airfoil_file' or 'naca', not both");
  if (!has_file && !has_naca) {
    if (required) table.fail({}, "[" + table.path() + "] needs 'airfoil_file' or 'naca'");
    return false;
  }
  const std::string key = has_file ? "airfoil_file" : "naca";
  const std::string where = table.where(key);
  try {
    if (has_file) {
      std::filesystem::path path;
      table.read_path(key, path);
      airfoil = read_airfoil_file(path);
    } else {
      std::string digits;
      table.read(key, digits);
      airfoil = naca_airfoil(digits, naca);
    }
  } catch (const Error& error) {
    // Errors from the airfoil file already name it; prefix the config position once.
    const std::string message = error.what();
    if (message.rfind(where, 0) == 0) throw;
    throw Error(where + ": " + message);
  }
  return true;
}

}  // namespace

WingDefinition read_wing_definition(config::Section& table) {
  NacaOptions naca;
  table.read("naca_points_per_side", naca.points_per_side, config::Bounds::at_least(5));
  table.read("naca_closed_trailing_edge", naca.closed_trailing_edge);
  std::string trailing_edge = "close";
  table.read_choice("blunt_trailing_edge", trailing_edge, {"close", "base"});
  double twist_axis = 0.25;
  table.read("twist_axis", twist_axis, config::Bounds::between(0.0, 1.0));

  std::vector<config::Section> stations = table.sections("station");
  WingDefinition wing;
  Airfoil airfoil;
  const bool wing_airfoil = read_airfoil(table, naca, stations.empty(), airfoil);
  if (stations.empty()) {
    ClassicPlanform planform;
    table.require("root_chord", planform.root_chord, config::Bounds::positive());
    table.require("semi_span", planform.semi_span, config::Bounds::positive());
    table.read("leading_edge_sweep", planform.leading_edge_sweep_degrees, {-80.0, 80.0, false, false});
    if (table.has("trailing_edge_sweep") == table.has("taper")) {
      table.fail(table.has("taper") ? "taper" : "", "give exactly one of 'trailing_edge_sweep' and 'taper'");
    }
    if (table.has("taper")) {
      double taper = 1.0;
      table.read("taper", taper, config::Bounds::positive());
      planform.taper = taper;
    } else {
      double sweep = 0.0;
      table.read("trailing_edge_sweep", sweep, {-80.0, 80.0, false, false});
      planform.trailing_edge_sweep_degrees = sweep;
    }
    table.read("root_twist", planform.root_twist_degrees, {-45.0, 45.0, false, false});
    table.read("tip_twist", planform.tip_twist_degrees, {-45.0, 45.0, false, false});
    table.read("dihedral", planform.dihedral_degrees, {-45.0, 45.0, false, false});
    try {
      wing = classic_wing(planform, airfoil);
    } catch (const Error& error) {
      table.fail(table.has("taper") ? "taper" : "trailing_edge_sweep", error.what());
    }
  } else {
    for (const std::string& key : classic_keys) {
      if (table.has(key))
        table.fail(
            key, "'" + key + "' is a classic planform key; with [[wing.station]] give every station instead");
    }
    if (wing_airfoil) wing.airfoils.push_back(airfoil);
    for (std::size_t k = 0; k < stations.size(); ++k) {
      config::Section& station_table = stations[k];
      SpanStation station;
      station_table.require("y", station.y, config::Bounds::non_negative());
      station_table.require("chord", station.chord, config::Bounds::positive());
      station_table.read("leading_edge_x", station.leading_edge_x);
      station_table.read("leading_edge_z", station.leading_edge_z);
      station_table.read("twist", station.twist_degrees, {-45.0, 45.0, false, false});
      Airfoil own;
      if (read_airfoil(station_table, naca, !wing_airfoil, own)) {
        station.airfoil = wing.airfoils.size();
        wing.airfoils.push_back(std::move(own));
      }
      if (k == 0 && station.y != 0.0)
        station_table.fail("y", "the first station must lie on the symmetry plane, y = 0");
      if (k > 0 && !(station.y > wing.stations.back().y)) {
        station_table.fail("y", "stations must be given with y increasing");
      }
      station_table.finish();
      wing.stations.push_back(station);
    }
    if (wing.stations.size() < 2) table.fail("station", "a wing needs at least two [[wing.station]] entries");
  }
  wing.twist_axis = twist_axis;
  wing.blunt_trailing_edge = trailing_edge == "base" ? TrailingEdge::base : TrailingEdge::close;
  table.finish();
  validate_wing(wing);
  return wing;
}

}  // namespace mixmesh
