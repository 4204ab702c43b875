// libFuzzer target for the SU2 reader: any input must either parse or throw
// mixmesh::Error; anything else (crash, other exception, hang, leak) is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "mixmesh/core/error.hpp"
#include "mixmesh/io/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    mixmesh::parse_su2(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.su2");
  } catch (const mixmesh::Error&) {
  }
  return 0;
}
