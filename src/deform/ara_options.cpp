// The ARA blend β(α) and the nearest-face cache file.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>

#include "deform/ara_geometry.hpp"
#include "mixmesh/core/atomic_file.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/deform/ara.hpp"

namespace mixmesh::deform {

double blend(double alpha, double gamma, BlendForm form) {
  const double clamped = std::clamp(alpha, 0.5, 1.0);
  if (form == BlendForm::linear) return clamped;
  // Eq. 11 (reconstructed): s = 2α − 1 runs from 0 on the median surface to 1 at the
  // boundary; an exponential rise in s, scaled to pass through (0, ½) and (1, 1).
  const double s = 2.0 * clamped - 1.0;
  if (gamma <= 0.0) return 0.5 + 0.5 * s;  // the limit γ → 0
  return 0.5 + 0.5 * (1.0 - std::exp(-gamma * s)) / (1.0 - std::exp(-gamma));
}

namespace {
// Version 2: magic, point, cell and wall-face counts, mesh hash, then the face pairs.
constexpr char cache_magic[8] = {'M', 'X', 'A', 'R', 'A', 'N', 'F', '2'};
constexpr char previous_magic[8] = {'M', 'X', 'A', 'R', 'A', 'N', 'F', '1'};
}  // namespace

void detail::write_nearest_part(std::ostream& stream, const NearestFaces& nearest) {
  const std::uint64_t counts[4] = {nearest.point_count, nearest.cell_count, nearest.wall_face_count,
                                   nearest.mesh_hash};
  stream.write(cache_magic, sizeof cache_magic);
  stream.write(reinterpret_cast<const char*>(counts), sizeof counts);
  if (!nearest.faces.empty())
    stream.write(reinterpret_cast<const char*>(nearest.faces.data()),
                 static_cast<std::streamsize>(nearest.faces.size() * sizeof(nearest.faces[0])));
}

void write_nearest_faces(const NearestFaces& nearest, const std::filesystem::path& file) {
  write_atomically(file, [&](const std::filesystem::path& temporary) {
    std::ofstream stream(temporary, std::ios::binary);
    if (!stream) throw Error(temporary.string() + ": cannot open for writing");
    detail::write_nearest_part(stream, nearest);
    if (!stream) throw Error(file.string() + ": write failed");
  });
}

namespace {

// The magic and the counts; the face pairs follow.
NearestFaces read_nearest_header(std::istream& stream, const std::filesystem::path& file) {
  char magic[8] = {};
  std::uint64_t counts[4] = {0, 0, 0, 0};
  stream.read(magic, sizeof magic);
  if (stream && std::memcmp(magic, previous_magic, sizeof magic) == 0)
    throw Error(file.string() + ": nearest-face cache of an older mixmesh (no mesh hash); delete it");
  stream.read(reinterpret_cast<char*>(counts), sizeof counts);
  if (!stream || std::memcmp(magic, cache_magic, sizeof magic) != 0)
    throw Error(file.string() + ": not a mixmesh nearest-face cache");
  for (int entry = 0; entry < 3; ++entry)
    if (counts[entry] > (std::uint64_t{1} << 34))
      throw Error(file.string() + ": implausible counts in the nearest-face cache");
  NearestFaces nearest;
  nearest.point_count = counts[0];
  nearest.cell_count = counts[1];
  nearest.wall_face_count = counts[2];
  nearest.mesh_hash = counts[3];
  return nearest;
}

}  // namespace

void detail::skip_nearest_part(std::istream& stream, const std::filesystem::path& file) {
  const NearestFaces header = read_nearest_header(stream, file);
  stream.seekg(static_cast<std::streamoff>(header.cell_count * sizeof(std::array<Index, 2>)), std::ios::cur);
}

NearestFaces read_nearest_faces(const std::filesystem::path& file) {
  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw Error(file.string() + ": cannot open the nearest-face cache");
  NearestFaces nearest = read_nearest_header(stream, file);
  nearest.faces.resize(nearest.cell_count);
  stream.read(reinterpret_cast<char*>(nearest.faces.data()),
              static_cast<std::streamsize>(nearest.faces.size() * sizeof(nearest.faces[0])));
  if (!stream) throw Error(file.string() + ": the nearest-face cache is truncated");
  for (const auto& pair : nearest.faces)
    for (Index face : pair)
      if (face < -1 || face >= static_cast<Index>(nearest.wall_face_count))
        throw Error(file.string() + ": face index " + std::to_string(face) + " out of range in the cache");
  return nearest;
}

}  // namespace mixmesh::deform
