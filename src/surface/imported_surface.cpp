#include "mixmesh/surface/imported_surface.hpp"

// OpenMesh 9's property containers trip GCC 12's -Wmaybe-uninitialized on default-
// constructed vectors (a false positive inside the library's templates).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#pragma GCC diagnostic pop

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "mixmesh/core/error.hpp"

namespace mixmesh {
namespace {

using PolygonMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

// Whitespace-separated numbers with the line each came from.
class NumberReader {
 public:
  explicit NumberReader(const std::filesystem::path& path) : path_(path), stream_(path) {
    if (!stream_) throw file_error(path.string(), 0, "cannot open the Plot3D file");
  }
  double next(const char* what) {
    while (!(line_stream_ >> token_)) {
      std::string text;
      if (!std::getline(stream_, text))
        throw file_error(path_.string(), line_, std::string("file ends before ") + what);
      ++line_;
      line_stream_.clear();
      line_stream_.str(text);
    }
    char* end = nullptr;
    const double value = std::strtod(token_.c_str(), &end);
    if (end == token_.c_str() || *end != '\0' || !std::isfinite(value)) {
      throw file_error(path_.string(), line_, std::string("expected ") + what + ", got '" + token_ + "'");
    }
    return value;
  }
  int next_count(const char* what) {
    const double value = next(what);
    if (value != std::floor(value) || value < 1 || value > 1e8) {
      throw file_error(path_.string(), line_, std::string(what) + " must be a positive whole number");
    }
    return static_cast<int>(value);
  }
  long line() const { return line_; }
  // Tokens left on the current line, moving to the next non-empty line first when the
  // current one is used up (tells "ni nj" from "ni nj nk" block headers).
  std::size_t tokens_on_line() {
    std::string rest;
    std::getline(line_stream_, rest);
    std::size_t count = 0;
    std::istringstream counter(rest);
    std::string token;
    while (counter >> token) ++count;
    std::string text = rest;
    while (count == 0) {
      if (!std::getline(stream_, text)) return 0;
      ++line_;
      std::istringstream next_counter(text);
      while (next_counter >> token) ++count;
    }
    line_stream_.clear();
    line_stream_.str(text);
    return count;
  }

 private:
  std::filesystem::path path_;
  std::ifstream stream_;
  std::istringstream line_stream_;
  std::string token_;
  long line_ = 0;
};

struct CellKey {
  std::int64_t x, y, z;
  bool operator==(const CellKey& other) const { return x == other.x && y == other.y && z == other.z; }
};
struct CellHash {
  std::size_t operator()(const CellKey& key) const {
    return static_cast<std::size_t>(key.x * 73856093LL ^ key.y * 19349663LL ^ key.z * 83492791LL);
  }
};

}  // namespace

SurfaceMesh read_plot3d_surface(const std::filesystem::path& path, const std::string& name) {
  NumberReader reader(path);
  const int blocks = reader.next_count("the block count");
  // Block headers: "ni nj nk" or "ni nj" per block, on one line or one line each.
  const std::size_t header_tokens = reader.tokens_on_line();
  std::size_t sizes_per_block = 0;
  if (header_tokens == 3 || header_tokens == 3 * static_cast<std::size_t>(blocks)) sizes_per_block = 3;
  if (header_tokens == 2 || header_tokens == 2 * static_cast<std::size_t>(blocks)) sizes_per_block = 2;
  if (sizes_per_block == 0) {
    throw file_error(path.string(), reader.line(),
                     "expected 'ni nj nk' or 'ni nj' for each of the " + std::to_string(blocks) + " blocks");
  }
  std::vector<std::array<int, 3>> headers;
  for (int block = 0; block < blocks; ++block) {
    std::array<int, 3> header = {reader.next_count("ni"), reader.next_count("nj"), 1};
    if (sizes_per_block == 3) header[2] = reader.next_count("nk");
    headers.push_back(header);
  }
  SurfaceMesh surface;
  for (int block = 0; block < blocks; ++block) {
    std::array<int, 3> header = headers[static_cast<std::size_t>(block)];
    // A surface block is one node thick in one direction; the other two are i and j.
    std::vector<int> dims;
    for (int size : header) {
      if (size > 1) dims.push_back(size);
    }
    if (dims.size() > 2) {
      throw file_error(path.string(), reader.line(),
                       "block " + std::to_string(block + 1) + " is a volume block, not a surface");
    }
    if (dims.size() < 2) {
      throw file_error(path.string(), reader.line(),
                       "block " + std::to_string(block + 1) + " needs at least 2 x 2 nodes");
    }
    const std::size_t count = static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]);
    if (count > 100'000'000) {
      throw file_error(path.string(), reader.line(), "block " + std::to_string(block + 1) + " is too large");
    }
    const Index first = static_cast<Index>(surface.points.size());
    surface.points.resize(surface.points.size() + count, Vector3::Zero());
    for (int axis = 0; axis < 3; ++axis) {
      for (std::size_t node = 0; node < count; ++node) {
        surface.points[static_cast<std::size_t>(first) + node][axis] = reader.next("a coordinate");
      }
    }
    StructuredPatch patch;
    patch.name = blocks == 1 ? name : name + "_" + std::to_string(block + 1);
    patch.ni = dims[0];
    patch.nj = dims[1];
    patch.nodes.resize(count);
    for (std::size_t node = 0; node < count; ++node) patch.nodes[node] = first + static_cast<Index>(node);
    surface.structured.push_back(std::move(patch));
  }
  return surface;
}

SurfaceMesh read_triangle_surface(const std::filesystem::path& path, const std::string& name) {
  if (!std::filesystem::exists(path)) throw file_error(path.string(), 0, "no such surface file");
  PolygonMesh mesh;
  OpenMesh::IO::Options read_options;
  if (!OpenMesh::IO::read_mesh(mesh, path.string(), read_options)) {
    throw file_error(path.string(), 0, "OpenMesh cannot read this file as STL, OBJ or OFF");
  }
  if (mesh.n_faces() == 0) throw file_error(path.string(), 0, "the surface file has no faces");
  SurfaceMesh surface;
  surface.points.reserve(mesh.n_vertices());
  for (const auto vertex : mesh.vertices()) {
    const auto point = mesh.point(vertex);
    surface.points.emplace_back(point[0], point[1], point[2]);
  }
  TrianglePatch patch;
  patch.name = name;
  for (const auto face : mesh.faces()) {
    std::vector<Index> corners;
    for (const auto vertex : mesh.fv_range(face)) corners.push_back(static_cast<Index>(vertex.idx()));
    // Fan polygons into triangles from their first corner.
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
      patch.triangles.insert(patch.triangles.end(), {corners[0], corners[k], corners[k + 1]});
    }
  }
  surface.unstructured.push_back(std::move(patch));
  return surface;
}

void append_surface(SurfaceMesh& whole, const SurfaceMesh& part) {
  const Index offset = static_cast<Index>(whole.points.size());
  whole.points.insert(whole.points.end(), part.points.begin(), part.points.end());
  for (StructuredPatch patch : part.structured) {
    for (Index& node : patch.nodes) node += offset;
    whole.structured.push_back(std::move(patch));
  }
  for (TrianglePatch patch : part.unstructured) {
    for (Index& node : patch.triangles) node += offset;
    whole.unstructured.push_back(std::move(patch));
  }
}

void merge_coincident_nodes(SurfaceMesh& surface, double tolerance) {
  if (!(tolerance > 0.0)) throw Error("merge tolerance must be positive");
  std::unordered_map<CellKey, std::vector<Index>, CellHash> grid;
  const auto key_of = [tolerance](const Vector3& point) {
    return CellKey{static_cast<std::int64_t>(std::floor(point.x() / tolerance)),
                   static_cast<std::int64_t>(std::floor(point.y() / tolerance)),
                   static_cast<std::int64_t>(std::floor(point.z() / tolerance))};
  };
  std::vector<Index> representative(surface.points.size());
  for (std::size_t node = 0; node < surface.points.size(); ++node) {
    const Vector3& point = surface.points[node];
    const CellKey key = key_of(point);
    Index found = -1;
    for (std::int64_t dx = -1; dx <= 1 && found < 0; ++dx) {
      for (std::int64_t dy = -1; dy <= 1 && found < 0; ++dy) {
        for (std::int64_t dz = -1; dz <= 1 && found < 0; ++dz) {
          const auto cell = grid.find({key.x + dx, key.y + dy, key.z + dz});
          if (cell == grid.end()) continue;
          for (Index other : cell->second) {
            if ((surface.points[static_cast<std::size_t>(other)] - point).norm() <= tolerance) {
              found = other;
              break;
            }
          }
        }
      }
    }
    if (found < 0) {
      found = static_cast<Index>(node);
      grid[key].push_back(found);
    }
    representative[node] = found;
  }
  // Renumber the surviving points in their order.
  std::vector<Index> renumber(surface.points.size(), -1);
  std::vector<Vector3> points;
  for (std::size_t node = 0; node < surface.points.size(); ++node) {
    if (representative[node] != static_cast<Index>(node)) continue;
    renumber[node] = static_cast<Index>(points.size());
    points.push_back(surface.points[node]);
  }
  const auto map = [&](Index node) {
    return renumber[static_cast<std::size_t>(representative[static_cast<std::size_t>(node)])];
  };
  for (StructuredPatch& patch : surface.structured) {
    for (Index& node : patch.nodes) node = map(node);
    for (int j = 0; j + 1 < patch.nj; ++j) {
      for (int i = 0; i + 1 < patch.ni; ++i) {
        std::array<Index, 4> quad = {patch.node(i, j), patch.node(i + 1, j), patch.node(i + 1, j + 1),
                                     patch.node(i, j + 1)};
        std::sort(quad.begin(), quad.end());
        if (std::adjacent_find(quad.begin(), quad.end()) != quad.end()) {
          throw Error("patch " + patch.name + ": face (i " + std::to_string(i) + ", j " + std::to_string(j) +
                      ") collapses when nodes closer than the merge tolerance are merged");
        }
      }
    }
  }
  for (TrianglePatch& patch : surface.unstructured) {
    for (Index& node : patch.triangles) node = map(node);
    for (std::size_t t = 0; t < patch.triangles.size(); t += 3) {
      const Index a = patch.triangles[t], b = patch.triangles[t + 1], c = patch.triangles[t + 2];
      if (a == b || b == c || c == a) {
        throw Error("patch " + patch.name + ": triangle " + std::to_string(t / 3) +
                    " collapses when nodes closer than the merge tolerance are merged");
      }
    }
  }
  surface.points = std::move(points);
}

SurfaceMesh import_surfaces(const std::vector<SurfaceImport>& imports, const ImportOptions& options) {
  SurfaceMesh whole;
  whole.symmetry_y = options.symmetry_y;
  whole.symmetry_tolerance = options.symmetry_tolerance;
  for (const SurfaceImport& import : imports) {
    std::string extension = import.file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const std::string name = import.name.empty() ? import.file.stem().string() : import.name;
    SurfaceMesh part;
    if (extension == ".p3d" || extension == ".xyz" || extension == ".g" || extension == ".x") {
      part = read_plot3d_surface(import.file, name);
    } else if (extension == ".stl" || extension == ".obj" || extension == ".off") {
      part = read_triangle_surface(import.file, name);
    } else {
      throw file_error(
          import.file.string(), 0,
          "unknown surface format '" + extension + "' (Plot3D .p3d/.xyz/.g/.x, or .stl/.obj/.off)");
    }
    for (StructuredPatch& patch : part.structured) {
      patch.role = import.role;
      if (!import.flip) continue;
      // Reversing i flips the normal (i x j).
      for (int j = 0; j < patch.nj; ++j) {
        auto row = patch.nodes.begin() + static_cast<std::ptrdiff_t>(j) * patch.ni;
        std::reverse(row, row + patch.ni);
      }
    }
    for (TrianglePatch& patch : part.unstructured) {
      patch.role = import.role;
      if (!import.flip) continue;
      for (std::size_t t = 0; t < patch.triangles.size(); t += 3)
        std::swap(patch.triangles[t + 1], patch.triangles[t + 2]);
    }
    append_surface(whole, part);
  }
  merge_coincident_nodes(whole, options.merge_tolerance);
  return whole;
}

}  // namespace mixmesh
