// The geometry block of the ARA cache file (see ara_geometry.hpp).
#include <cstring>
#include <fstream>
#include <type_traits>

#include "deform/ara_geometry.hpp"
#include "mixmesh/core/atomic_file.hpp"
#include "mixmesh/core/error.hpp"

namespace mixmesh::deform::detail {

namespace {

constexpr char geometry_magic[8] = {'M', 'X', 'A', 'R', 'A', 'G', 'E', '1'};
static_assert(sizeof(Vector3) == 3 * sizeof(double), "points are stored as three doubles");

// Every value written is also mixed into a checksum (combine_hash, dual_mesh.hpp), so
// that a truncated or damaged block is refused rather than half used.
class BlockWriter {
 public:
  explicit BlockWriter(std::ostream& stream) : stream_(stream) {}
  void word(std::uint64_t value) { bytes(reinterpret_cast<const char*>(&value), sizeof value); }
  template <class Value>
  void values(const std::vector<Value>& list) {
    static_assert(std::is_trivially_copyable_v<Value> || std::is_same_v<Value, Vector3>);
    word(list.size());
    bytes(reinterpret_cast<const char*>(list.data()), list.size() * sizeof(Value));
  }
  std::uint64_t checksum() const { return checksum_; }

 private:
  void bytes(const char* data, std::size_t count) {
    if (count > 0) stream_.write(data, static_cast<std::streamsize>(count));
    checksum_ = combine_hash(checksum_, data, count);
  }
  std::ostream& stream_;
  std::uint64_t checksum_ = 0x61726167656full;
};

class BlockReader {
 public:
  BlockReader(std::istream& stream, std::uint64_t remaining, const std::filesystem::path& file)
      : stream_(stream), remaining_(remaining), file_(file) {}
  std::uint64_t word() {
    std::uint64_t value = 0;
    bytes(reinterpret_cast<char*>(&value), sizeof value);
    return value;
  }
  template <class Value>
  void values(std::vector<Value>& list) {
    const std::uint64_t count = word();
    if (count > remaining_ / sizeof(Value)) damaged("a list longer than the file");
    list.resize(count);
    bytes(reinterpret_cast<char*>(list.data()), count * sizeof(Value));
  }
  std::uint64_t checksum() const { return checksum_; }
  [[noreturn]] void damaged(const std::string& what) const {
    throw Error(file_.string() + ": the geometry in the ARA cache is damaged (" + what +
                "); delete the file");
  }

 private:
  void bytes(char* data, std::size_t count) {
    if (count > remaining_) damaged("truncated");
    if (count > 0) stream_.read(data, static_cast<std::streamsize>(count));
    if (!stream_) damaged("truncated");
    remaining_ -= count;
    checksum_ = combine_hash(checksum_, data, count);
  }
  std::istream& stream_;
  std::uint64_t remaining_;
  const std::filesystem::path& file_;
  std::uint64_t checksum_ = 0x61726167656full;
};

// The same members in the same order for writing and reading.
template <class Block, class Geometry>
void transfer(Block& block, Geometry& geometry) {
  auto& dual = geometry.dual;
  block.values(dual.cell_offsets);
  block.values(dual.cell_nodes);
  block.values(dual.cell_kind);
  block.values(dual.index_in_block);
  block.values(dual.interior_cells);
  block.values(dual.interior_area);
  block.values(dual.face_offsets);
  block.values(dual.face_nodes);
  block.values(dual.face_marker);
  block.values(dual.face_cell);
  block.values(dual.point_cell_offsets);
  block.values(dual.point_cells);
  block.values(geometry.walls.faces);
  block.values(geometry.walls.boundary);
  block.values(geometry.centres);
  block.values(geometry.wall_centres);
  auto& stencil = geometry.stencil;
  block.values(stencil.offsets);
  block.values(stencil.neighbour);
  block.values(stencil.weight);
  block.values(stencil.wall_offsets);
  block.values(stencil.wall);
  block.values(stencil.wall_weight);
  block.values(stencil.diagonal);
  block.values(geometry.node_weights);
}

// Sizes that the solver and the interpolation index by: a block that passed its
// checksum but disagrees here was written by a different layout.
bool consistent(const AraGeometry& geometry) {
  const DualMesh& dual = geometry.dual;
  const std::size_t cells = dual.cell_kind.size();
  if (dual.cell_offsets.empty() || dual.point_cell_offsets.empty() || geometry.stencil.offsets.empty())
    return false;
  return dual.cell_offsets.size() == cells + 1 && dual.index_in_block.size() == cells &&
         dual.interior_area.size() == dual.interior_cells.size() &&
         dual.face_offsets.size() == dual.face_marker.size() + 1 &&
         dual.face_cell.size() == dual.face_marker.size() &&
         dual.point_cell_offsets.size() == dual.point_count + 1 &&
         geometry.walls.boundary.size() == geometry.walls.faces.size() && geometry.centres.size() == cells &&
         geometry.wall_centres.size() == geometry.walls.faces.size() &&
         geometry.stencil.offsets.size() == cells + 1 && geometry.stencil.diagonal.size() == cells &&
         geometry.stencil.wall_offsets.size() == cells + 1 &&
         geometry.node_weights.size() == dual.point_cells.size() &&
         dual.cell_offsets.back() == dual.cell_nodes.size() &&
         dual.point_cell_offsets.back() == dual.point_cells.size() &&
         geometry.stencil.offsets.back() == geometry.stencil.neighbour.size();
}

}  // namespace

void write_ara_cache(const NearestFaces& nearest, const AraGeometry& geometry,
                     const std::filesystem::path& file) {
  write_atomically(file, [&](const std::filesystem::path& temporary) {
    std::ofstream stream(temporary, std::ios::binary);
    if (!stream) throw Error(temporary.string() + ": cannot open for writing");
    write_nearest_part(stream, nearest);
    stream.write(geometry_magic, sizeof geometry_magic);
    BlockWriter block(stream);
    block.word(geometry.connectivity);
    block.word(geometry.points);
    block.word(geometry.nearest_key);
    block.values(geometry.marker_roles);
    block.word(geometry.dual.planar ? 1 : 0);
    block.word(geometry.dual.point_count);
    block.word(static_cast<std::uint64_t>(geometry.walls.boundary_count));
    transfer(block, geometry);
    const std::uint64_t checksum = block.checksum();
    stream.write(reinterpret_cast<const char*>(&checksum), sizeof checksum);
    if (!stream) throw Error(file.string() + ": write failed");
  });
}

StoredGeometry read_ara_geometry(const std::filesystem::path& file, std::uint64_t connectivity,
                                 std::uint64_t points, const std::vector<MarkerRole>& marker_roles) {
  StoredGeometry result;
  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw Error(file.string() + ": cannot open the ARA cache");
  const std::uint64_t size = std::filesystem::file_size(file);
  skip_nearest_part(stream, file);
  if (stream.peek() == std::char_traits<char>::eof()) {
    result.faces_only = true;
    result.why_not = "the file holds nearest faces only";
    return result;
  }
  char magic[8] = {};
  stream.read(magic, sizeof magic);
  if (!stream || std::memcmp(magic, geometry_magic, sizeof magic) != 0) {
    result.why_not = "its geometry block is of another format";
    return result;
  }
  BlockReader block(stream, size - static_cast<std::uint64_t>(stream.tellg()), file);
  auto geometry = std::make_shared<AraGeometry>();
  geometry->connectivity = block.word();
  geometry->points = block.word();
  if (geometry->connectivity != connectivity || geometry->points != points) {
    result.why_not =
        geometry->connectivity != connectivity ? "it was made for other cells" : "the points moved";
    return result;
  }
  geometry->nearest_key = block.word();
  block.values(geometry->marker_roles);
  if (geometry->marker_roles != marker_roles) {
    result.why_not = "the markers' roles differ";
    return result;
  }
  geometry->dual.planar = block.word() != 0;
  geometry->dual.point_count = block.word();
  geometry->walls.boundary_count = static_cast<int>(block.word());
  transfer(block, *geometry);
  const std::uint64_t computed = block.checksum();
  std::uint64_t stored = 0;
  stream.read(reinterpret_cast<char*>(&stored), sizeof stored);
  if (!stream || stored != computed) block.damaged("checksum");
  if (!consistent(*geometry)) block.damaged("inconsistent sizes");
  result.geometry = std::move(geometry);
  return result;
}

}  // namespace mixmesh::deform::detail
