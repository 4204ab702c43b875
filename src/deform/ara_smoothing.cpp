// The ARA smoothing system and its solvers (Martineau & Georgala eq. 12–21).
#include "deform/ara_smoothing.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mixmesh::deform::detail {

namespace {

// Sum of body(item, sum) over all items in fixed chunks added in a fixed order: the
// same bits whatever the number of threads (a tbb::parallel_reduce would not be).
constexpr std::size_t chunk_size = 4096;

template <class Sum, class Body>
Sum chunked_sum(std::size_t count, const Body& body) {
  const std::size_t chunks = (count + chunk_size - 1) / chunk_size;
  std::vector<Sum> partial(chunks, Sum::Zero());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t chunk = range.begin(); chunk != range.end(); ++chunk) {
                        Sum sum = Sum::Zero();
                        const std::size_t end = std::min(count, (chunk + 1) * chunk_size);
                        for (std::size_t item = chunk * chunk_size; item < end; ++item) body(item, sum);
                        partial[chunk] = sum;
                      }
                    });
  Sum total = Sum::Zero();
  for (const Sum& sum : partial) total += sum;
  return total;
}

// Σ_j σ_ij v_j over the interior neighbours of `cell`.
Vector3 neighbour_sum(const SmoothingStencil& stencil, const std::vector<Vector3>& values, std::size_t cell) {
  Vector3 sum = Vector3::Zero();
  for (std::size_t entry = stencil.offsets[cell]; entry < stencil.offsets[cell + 1]; ++entry)
    sum += stencil.weight[entry] * values[static_cast<std::size_t>(stencil.neighbour[entry])];
  return sum;
}

// Componentwise a / b with 0 where b is 0 (a component whose residual already vanished).
Vector3 safe_quotient(const Vector3& numerator, const Vector3& denominator) {
  Vector3 quotient;
  for (int axis = 0; axis < 3; ++axis)
    quotient[axis] = denominator[axis] != 0.0 ? numerator[axis] / denominator[axis] : 0.0;
  return quotient;
}

}  // namespace

SmoothingStencil build_smoothing_stencil(const DualMesh& dual, const WallFaces& walls,
                                         const std::vector<Vector3>& centres,
                                         const std::vector<Vector3>& wall_centres,
                                         const std::vector<double>& diffusivity,
                                         const std::vector<Vector3>& points) {
  const std::size_t cells = dual.cell_count();
  constexpr double tiny = 1e-300;
  SmoothingStencil stencil;
  stencil.offsets.assign(cells + 1, 0);
  for (const auto& pair : dual.interior_cells) {
    ++stencil.offsets[static_cast<std::size_t>(pair[0]) + 1];
    ++stencil.offsets[static_cast<std::size_t>(pair[1]) + 1];
  }
  for (std::size_t cell = 0; cell < cells; ++cell) stencil.offsets[cell + 1] += stencil.offsets[cell];
  stencil.neighbour.resize(stencil.offsets.back());
  stencil.weight.resize(stencil.offsets.back());
  std::vector<std::size_t> fill(stencil.offsets.begin(), stencil.offsets.end() - 1);
  for (std::size_t pair_index = 0; pair_index < dual.interior_cells.size(); ++pair_index) {
    const std::size_t a = static_cast<std::size_t>(dual.interior_cells[pair_index][0]);
    const std::size_t b = static_cast<std::size_t>(dual.interior_cells[pair_index][1]);
    // Baker's diffusivity at the face, eq. 17; σ = τ A / |x_i − x_j|, eq. 20.
    const double tau = 0.5 * (diffusivity[a] + diffusivity[b]);
    const double sigma =
        tau * dual.interior_area[pair_index] / std::max((centres[a] - centres[b]).norm(), tiny);
    stencil.neighbour[fill[a]] = static_cast<Index>(b);
    stencil.weight[fill[a]++] = sigma;
    stencil.neighbour[fill[b]] = static_cast<Index>(a);
    stencil.weight[fill[b]++] = sigma;
  }
  // Neighbours in increasing order: the sums then run through memory forwards.
  parallel_items(cells, [&](std::size_t cell) {
    const std::size_t begin = stencil.offsets[cell];
    const std::size_t count = stencil.offsets[cell + 1] - begin;
    for (std::size_t next = 1; next < count; ++next)
      for (std::size_t slot = begin + next;
           slot > begin && stencil.neighbour[slot - 1] > stencil.neighbour[slot]; --slot) {
        std::swap(stencil.neighbour[slot - 1], stencil.neighbour[slot]);
        std::swap(stencil.weight[slot - 1], stencil.weight[slot]);
      }
  });

  stencil.wall_offsets.assign(cells + 1, 0);
  for (Index face : walls.faces) ++stencil.wall_offsets[static_cast<std::size_t>(dual.face_cell[face]) + 1];
  for (std::size_t cell = 0; cell < cells; ++cell)
    stencil.wall_offsets[cell + 1] += stencil.wall_offsets[cell];
  stencil.wall.resize(walls.faces.size());
  stencil.wall_weight.resize(walls.faces.size());
  fill.assign(stencil.wall_offsets.begin(), stencil.wall_offsets.end() - 1);
  for (std::size_t wall = 0; wall < walls.faces.size(); ++wall) {
    const std::size_t face = static_cast<std::size_t>(walls.faces[wall]);
    const std::size_t cell = static_cast<std::size_t>(dual.face_cell[face]);
    const double distance = (centres[cell] - wall_centres[wall]).norm();
    stencil.wall[fill[cell]] = static_cast<Index>(wall);
    stencil.wall_weight[fill[cell]++] =
        diffusivity[cell] * face_area(dual, face, points) / std::max(distance, tiny);
  }

  stencil.diagonal.assign(cells, 0.0);
  parallel_items(cells, [&](std::size_t cell) {
    double sum = 0.0;
    for (std::size_t entry = stencil.offsets[cell]; entry < stencil.offsets[cell + 1]; ++entry)
      sum += stencil.weight[entry];
    for (std::size_t entry = stencil.wall_offsets[cell]; entry < stencil.wall_offsets[cell + 1]; ++entry)
      sum += stencil.wall_weight[entry];
    stencil.diagonal[cell] = sum;
  });
  return stencil;
}

std::vector<Vector3> smoothing_source(const SmoothingStencil& stencil,
                                      const std::vector<Vector3>& wall_values, const Transport& transport) {
  const std::size_t cells = stencil.diagonal.size();
  const bool transported = transport.cell_turn != nullptr;
  std::vector<Vector3> source(cells);
  parallel_items(cells, [&](std::size_t cell) {
    Vector3 sum = Vector3::Zero();
    for (std::size_t entry = stencil.wall_offsets[cell]; entry < stencil.wall_offsets[cell + 1]; ++entry) {
      const std::size_t wall = static_cast<std::size_t>(stencil.wall[entry]);
      Vector3 value = wall_values[wall];
      // u_w + (R_w − I)(x_i − x_w): the wall face's motion carried rigidly to the cell.
      if (transported)
        value +=
            (*transport.wall_turn)[wall] * ((*transport.centres)[cell] - (*transport.wall_centres)[wall]);
      sum += stencil.wall_weight[entry] * value;
    }
    if (transported) {
      const Vector3& centre = (*transport.centres)[cell];
      for (std::size_t entry = stencil.offsets[cell]; entry < stencil.offsets[cell + 1]; ++entry) {
        const std::size_t other = static_cast<std::size_t>(stencil.neighbour[entry]);
        sum +=
            stencil.weight[entry] * ((*transport.cell_turn)[other] * (centre - (*transport.centres)[other]));
      }
    }
    source[cell] = sum;
  });
  return source;
}

SolveResult gauss_seidel(std::vector<Vector3>& values, const std::vector<Vector3>& source,
                         const SmoothingStencil& stencil, const std::vector<std::vector<Index>>& colours,
                         const SolveSettings& settings) {
  const std::size_t cells = values.size();
  SolveResult result;
  if (cells == 0 || settings.scale <= 0.0) return result;
  std::vector<double> change(cells, 0.0);
  const double epsilon = settings.relaxation;
  result.residual = std::numeric_limits<double>::infinity();
  while (result.iterations < settings.max_iterations) {
    ++result.iterations;
    for (const auto& colour : colours) {
      parallel_items(colour.size(), [&](std::size_t slot) {
        const std::size_t cell = static_cast<std::size_t>(colour[slot]);
        const double weight = stencil.diagonal[cell];
        if (weight <= 0.0) return;
        const Vector3 target = (neighbour_sum(stencil, values, cell) + source[cell]) / weight;
        change[cell] = (target - values[cell]).squaredNorm();
        values[cell] = (1.0 - epsilon) * values[cell] + epsilon * target;  // eq. 19
      });
    }
    double total = 0.0;
    for (double entry : change) total += entry;
    result.residual = std::sqrt(total / static_cast<double>(cells)) / settings.scale;
    if (result.residual <= settings.tolerance) break;
  }
  return result;
}

SolveResult conjugate_gradient(std::vector<Vector3>& values, const std::vector<Vector3>& source,
                               const SmoothingStencil& stencil, const SolveSettings& settings) {
  const std::size_t cells = values.size();
  SolveResult result;
  if (cells == 0 || settings.scale <= 0.0) return result;
  // A cell without neighbours (zero diagonal) keeps its value: its residual, search
  // direction and preconditioned residual stay zero.
  std::vector<double> inverse(cells);
  for (std::size_t cell = 0; cell < cells; ++cell)
    inverse[cell] = stencil.diagonal[cell] > 0.0 ? 1.0 / stencil.diagonal[cell] : 0.0;
  auto product = [&](const std::vector<Vector3>& vector, std::size_t cell) -> Vector3 {
    if (inverse[cell] == 0.0) return Vector3::Zero();
    return stencil.diagonal[cell] * vector[cell] - neighbour_sum(stencil, vector, cell);
  };
  using Sums = Eigen::Vector4d;  // r·z per component, |z|²
  std::vector<Vector3> residual(cells);
  std::vector<Vector3> direction(cells);
  std::vector<Vector3> image(cells);
  Sums sums = chunked_sum<Sums>(cells, [&](std::size_t cell, Sums& sum) {
    residual[cell] = inverse[cell] == 0.0 ? Vector3::Zero() : Vector3(source[cell] - product(values, cell));
    const Vector3 preconditioned = inverse[cell] * residual[cell];
    direction[cell] = preconditioned;
    sum.head<3>() += residual[cell].cwiseProduct(preconditioned);
    sum[3] += preconditioned.squaredNorm();
  });
  auto rms = [&](const Sums& entry) {
    return std::sqrt(entry[3] / static_cast<double>(cells)) / settings.scale;
  };
  result.residual = rms(sums);
  while (result.residual > settings.tolerance && result.iterations < settings.max_iterations) {
    ++result.iterations;
    const Vector3 curvature = chunked_sum<Vector3>(cells, [&](std::size_t cell, Vector3& sum) {
      image[cell] = product(direction, cell);
      sum += direction[cell].cwiseProduct(image[cell]);
    });
    const Vector3 step = safe_quotient(sums.head<3>(), curvature);
    const Sums next = chunked_sum<Sums>(cells, [&](std::size_t cell, Sums& sum) {
      values[cell] += step.cwiseProduct(direction[cell]);
      residual[cell] -= step.cwiseProduct(image[cell]);
      const Vector3 preconditioned = inverse[cell] * residual[cell];
      sum.head<3>() += residual[cell].cwiseProduct(preconditioned);
      sum[3] += preconditioned.squaredNorm();
    });
    result.residual = rms(next);
    if (result.residual <= settings.tolerance) break;
    const Vector3 conjugation = safe_quotient(next.head<3>(), sums.head<3>());
    sums = next;
    parallel_items(cells, [&](std::size_t cell) {
      direction[cell] = inverse[cell] * residual[cell] + conjugation.cwiseProduct(direction[cell]);
    });
  }
  return result;
}

}  // namespace mixmesh::deform::detail
