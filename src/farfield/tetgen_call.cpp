// The TetGen 1.5 call: PLC in, tetrahedra out, errors as mixmesh::Error.

#define TETLIBRARY  // the library build of TetGen: errors are thrown, not exit()
#include <tetgen.h>

#include <cstdlib>
#include <sstream>
#include <string>

#include "farfield/farfield_parts.hpp"
#include "farfield/isolated_call.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"

namespace mixmesh::farfield_detail {

void use_single_free_termination();  // tetgen_terminate.cpp

namespace {

// Fills a tetgenio with the points, sizes and boundary triangles (tetgenio frees
// what it holds with delete[]).
void fill(tetgenio& io, const TetgenInput& input, bool with_sizes) {
  io.firstnumber = 0;
  io.numberofpoints = static_cast<int>(input.points.size());
  io.pointlist = new REAL[3 * input.points.size()];
  for (std::size_t point = 0; point < input.points.size(); ++point)
    for (int axis = 0; axis < 3; ++axis)
      io.pointlist[3 * point + static_cast<std::size_t>(axis)] = input.points[point](axis);
  if (with_sizes) {
    io.numberofpointmtrs = 1;
    io.pointmtrlist = new REAL[input.sizes.size()];
    std::copy(input.sizes.begin(), input.sizes.end(), io.pointmtrlist);
  }
  io.numberoffacets = static_cast<int>(input.triangles.size());
  io.facetlist = new tetgenio::facet[input.triangles.size()];
  io.facetmarkerlist = new int[input.triangles.size()];
  for (std::size_t face = 0; face < input.triangles.size(); ++face) {
    tetgenio::facet& facet = io.facetlist[face];
    tetgenio::init(&facet);
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&facet.polygonlist[0]);
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3];
    for (int corner = 0; corner < 3; ++corner)
      facet.polygonlist[0].vertexlist[corner] = input.triangles[face][static_cast<std::size_t>(corner)];
    io.facetmarkerlist[face] = static_cast<int>(face) + 1;
  }
  io.numberofholes = static_cast<int>(input.holes.size());
  io.holelist = new REAL[3 * input.holes.size() + 1];
  for (std::size_t hole = 0; hole < input.holes.size(); ++hole)
    for (int axis = 0; axis < 3; ++axis)
      io.holelist[3 * hole + static_cast<std::size_t>(axis)] = input.holes[hole](axis);
}

// `flip_dihedral` (degrees, 0: TetGen's own bounds): the largest dihedral angle above
// which TetGen's optimisation flips a tetrahedron. Without -q TetGen's parser raises
// its flip bounds to 179° (only nearly flat tetrahedra are flipped); the bound and the
// -q smoothing and splitting bounds are set again, so flips remove slivers without
// refining anything.
void run(const std::string& switches, tetgenio& in, tetgenio& out, double flip_dihedral = 0.0) {
  tetgenbehavior behaviour;
  std::vector<char> text(switches.begin(), switches.end());
  text.push_back('\0');
  if (!behaviour.parse_commandline(text.data()))
    throw Error("farfield: TetGen rejected the switches " + switches);
  if (flip_dihedral > 0.0) {
    behaviour.optmaxdihedral = flip_dihedral;
    behaviour.optminsmtdihed = 179.0;
    behaviour.optminslidihed = 179.0;
  }
  use_single_free_termination();
  tetrahedralize(&behaviour, &in, &out);
}

// Asks TetGen (-d) which boundary triangles intersect: their count (0: none, or the
// test failed) and the centre of the first.
IntersectionFound find_intersections(const TetgenInput& input) {
  tetgenio in, out;
  fill(in, input, false);
  try {
    run("pdQz", in, out);
  } catch (int) {
    return {};
  }
  if (out.numberoftrifaces <= 0 || out.trifacelist == nullptr) return {};
  IntersectionFound found;
  found.count = static_cast<std::size_t>(out.numberoftrifaces);
  for (std::size_t face = 0; face < found.count; ++face) {
    Vector3 centre = Vector3::Zero();
    for (std::size_t corner = 0; corner < 3; ++corner) {
      const int node = out.trifacelist[3 * face + corner];
      centre +=
          Vector3(out.pointlist[3 * node], out.pointlist[3 * node + 1], out.pointlist[3 * node + 2]) / 3.0;
    }
    found.centres.push_back(centre);
  }
  found.first = found.centres.front();
  return found;
}

// The tetrahedralisation itself; throws mixmesh::Error for the failures TetGen
// reports (its exit codes of tetgenmesh::terminatetetgen).
TetgenOutput tetrahedralise(const TetgenInput& input) {
  tetgenio in, out;
  const bool with_sizes = input.quality && !input.sizes.empty();
  fill(in, input, with_sizes);
  // p: PLC; Y: no Steiner points on the boundary; q: radius-edge bound; m: sizes;
  // J: keep every input point so indices stay; z: zero-based; Q: quiet.
  std::ostringstream switches;
  switches << "pY";
  if (input.quality) switches << "q" << input.radius_edge_ratio << (with_sizes ? "m" : "");
  switches << "JzQ";
  try {
    run(switches.str(), in, out, input.flip_dihedral);
  } catch (int code) {
    switch (code) {
      case 1:
        throw Error("farfield: TetGen ran out of memory");
      case 3:
        throw Error("farfield: the boundary intersects itself");
      case 4:
        throw Error("farfield: the boundary has a feature too small for TetGen's tolerance");
      case 5:
        throw Error("farfield: two boundary triangles are too close");
      default:
        throw Error("farfield: TetGen failed (code " + std::to_string(code) + ")");
    }
  }

  TetgenOutput result;
  result.points.resize(static_cast<std::size_t>(out.numberofpoints));
  for (std::size_t point = 0; point < result.points.size(); ++point)
    result.points[point] =
        Vector3(out.pointlist[3 * point], out.pointlist[3 * point + 1], out.pointlist[3 * point + 2]);
  for (std::size_t point = 0; point < input.points.size(); ++point)
    if (point >= result.points.size() || result.points[point] != input.points[point])
      throw Error("farfield: TetGen renumbered the boundary point " + point_text(input.points[point]) +
                  " (duplicate boundary points?)");
  if (out.numberofcorners != 4)
    throw Error("farfield: TetGen returned tetrahedra of " + std::to_string(out.numberofcorners) + " nodes");
  result.tetrahedra.resize(static_cast<std::size_t>(out.numberoftetrahedra));
  for (std::size_t tetrahedron = 0; tetrahedron < result.tetrahedra.size(); ++tetrahedron)
    for (int corner = 0; corner < 4; ++corner)
      result.tetrahedra[tetrahedron][static_cast<std::size_t>(corner)] =
          out.tetrahedronlist[4 * tetrahedron + static_cast<std::size_t>(corner)];
  return result;
}

}  // namespace

// The child's result through the pipe (Eigen vectors as plain doubles).
void send(isolated_detail::Channel& channel, const TetgenOutput& output) {
  std::vector<double> coordinates;
  coordinates.reserve(3 * output.points.size());
  for (const Vector3& point : output.points)
    coordinates.insert(coordinates.end(), {point.x(), point.y(), point.z()});
  channel.write_vector(coordinates);
  channel.write_vector(output.tetrahedra);
}

bool receive(isolated_detail::Channel& channel, TetgenOutput& output) {
  std::vector<double> coordinates;
  if (!channel.read_vector(coordinates) || !channel.read_vector(output.tetrahedra)) return false;
  output.points.resize(coordinates.size() / 3);
  for (std::size_t point = 0; point < output.points.size(); ++point)
    output.points[point] =
        Vector3(coordinates[3 * point], coordinates[3 * point + 1], coordinates[3 * point + 2]);
  return true;
}

void send(isolated_detail::Channel& channel, const IntersectionFound& found) {
  std::vector<double> values{static_cast<double>(found.count)};
  for (const Vector3& centre : found.centres)
    values.insert(values.end(), {centre.x(), centre.y(), centre.z()});
  channel.write_vector(values);
}

bool receive(isolated_detail::Channel& channel, IntersectionFound& found) {
  std::vector<double> values;
  if (!channel.read_vector(values) || values.empty() || (values.size() - 1) % 3 != 0) return false;
  found.count = static_cast<std::size_t>(values[0]);
  found.centres.clear();
  for (std::size_t k = 1; k < values.size(); k += 3)
    found.centres.emplace_back(values[k], values[k + 1], values[k + 2]);
  if (found.count > 0 && found.centres.empty()) return false;
  if (!found.centres.empty()) found.first = found.centres.front();
  return true;
}

namespace {

double volume6(const std::vector<Vector3>& points, const std::array<Index, 4>& tetrahedron) {
  auto at = [&](int corner) -> const Vector3& {
    return points[static_cast<std::size_t>(tetrahedron[static_cast<std::size_t>(corner)])];
  };
  return tetrahedron_volume6(at(0), at(1), at(2), at(3));
}

}  // namespace

bool negative_orientation(const std::vector<Vector3>& points,
                          const std::vector<std::array<Index, 4>>& tetrahedra) {
  std::size_t negative = 0;
  for (const auto& tetrahedron : tetrahedra) negative += volume6(points, tetrahedron) < 0.0;
  return 2 * negative > tetrahedra.size();
}

std::size_t flat_tetrahedra(const std::vector<Vector3>& points,
                            const std::vector<std::array<Index, 4>>& tetrahedra, bool negative,
                            Vector3* first) {
  const double sign = negative ? -1.0 : 1.0;
  std::size_t flat = 0;
  for (const auto& tetrahedron : tetrahedra) {
    if (sign * volume6(points, tetrahedron) > 0.0) continue;
    if (flat++ == 0 && first) *first = cell_centre(CellType::tetrahedron, points, tetrahedron.data());
  }
  return flat;
}

TetgenOutput run_tetgen(const TetgenInput& input) {
  // TetGen runs in a child process and only its result (or its error) comes back: a
  // run can be stopped at its time limit, and a crash inside TetGen does not take the
  // program down. (TetGen 1.5.0 freed its memory twice on every error it stopped on;
  // tetgen_terminate.cpp mends that, so its error codes arrive.)
  // Fault injection for the fallbacks' regression tests: MIXMESH_TETGEN_ABORT=N makes
  // the N-th tetrahedralisation of the process abort in its child, as TetGen 1.5 does
  // on an internal assertion (the inputs that once did so mesh since the far field
  // changed, and its fallbacks would otherwise go untested).
  static int runs = 0;
  const char* abort_run = std::getenv("MIXMESH_TETGEN_ABORT");
  const bool inject_abort = abort_run && std::atoi(abort_run) == ++runs;
  try {
    return run_isolated<TetgenOutput>(
        "TetGen",
        [&] {
          if (inject_abort) std::abort();
          return tetrahedralise(input);
        },
        input.time_limit_seconds);
  } catch (const TimeLimitError&) {
    throw;  // the caller's fallback; no intersection test after a timeout
  } catch (const Error&) {
    // Where TetGen's own test (-d) finds intersecting boundary triangles, that is
    // the cause to report, whatever the failure looked like.
    IntersectionFound found;
    try {
      found = run_isolated<IntersectionFound>("TetGen's intersection test",
                                              [&] { return find_intersections(input); });
    } catch (const Error&) {
    }
    if (found.count > 0)
      throw HullIntersectionError("farfield: the boundary intersects itself (" + std::to_string(found.count) +
                                      " intersecting boundary triangles, the first near " +
                                      point_text(found.first) + ")",
                                  found.centres);
    throw;
  }
}

}  // namespace mixmesh::farfield_detail
