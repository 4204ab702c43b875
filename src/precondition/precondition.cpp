#include "mixmesh/precondition/precondition.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <fstream>
#include <iomanip>

#include "mixmesh/core/atomic_file.hpp"
#include "mixmesh/core/error.hpp"

namespace mixmesh {

double estimate_sweep_degrees(const std::vector<Vector3>& points) {
  if (points.empty()) return 0.0;
  double low = points.front().y(), high = low;
  for (const Vector3& point : points) {
    low = std::min(low, point.y());
    high = std::max(high, point.y());
  }
  if (!(high - low > 0.0)) return 0.0;
  constexpr int stations = 10;
  std::vector<Vector3> leading(stations, Vector3::Constant(std::numeric_limits<double>::infinity()));
  for (const Vector3& point : points) {
    const int station = std::min(stations - 1, static_cast<int>((point.y() - low) / (high - low) * stations));
    if (point.x() < leading[static_cast<std::size_t>(station)].x())
      leading[static_cast<std::size_t>(station)] = point;
  }
  // Least-squares line x = a + b y through the leading-edge points of the stations.
  double count = 0, sum_y = 0, sum_x = 0, sum_yy = 0, sum_xy = 0;
  for (const Vector3& point : leading) {
    if (!std::isfinite(point.x())) continue;
    ++count;
    sum_y += point.y();
    sum_x += point.x();
    sum_yy += point.y() * point.y();
    sum_xy += point.x() * point.y();
  }
  const double denominator = count * sum_yy - sum_y * sum_y;
  if (count < 2 || !(denominator > 0.0)) return 0.0;
  const double slope = (count * sum_xy - sum_x * sum_y) / denominator;
  return std::asin(std::clamp(slope, -0.95, 0.95)) * 180.0 / M_PI;
}

Preconditioning precondition(const std::vector<Vector3>& points,
                             const std::vector<std::array<Index, 3>>& triangles,
                             const PreconditionOptions& options) {
  Preconditioning result;
  if (options.shear) {
    result.sweep_degrees =
        std::isnan(options.sweep_degrees) ? estimate_sweep_degrees(points) : options.sweep_degrees;
    result.shear(0, 1) = std::sin(result.sweep_degrees * M_PI / 180.0);  // Wild eq. (14)
  }
  const Eigen::Matrix3d unshear = result.shear.inverse();

  // Wild eqs. (16)–(17) on the sheared points: Ā = Σ_i n A_i / Σ_j |x_j − x_c|², i.e.
  // the sum of the trace-normalised node covariances of the triangles.
  Eigen::Matrix3d mean = Eigen::Matrix3d::Zero();
  int used = 0;
  for (const auto& triangle : triangles) {
    Vector3 corner[3];
    for (int local = 0; local < 3; ++local)
      corner[local] =
          unshear * points.at(static_cast<std::size_t>(triangle[static_cast<std::size_t>(local)]));
    const Vector3 centre = (corner[0] + corner[1] + corner[2]) / 3.0;
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    double spread = 0.0;
    for (const Vector3& point : corner) {
      covariance += (point - centre) * (point - centre).transpose();
      spread += (point - centre).squaredNorm();
    }
    if (!(spread > 0.0)) continue;
    mean += covariance / spread;
    ++used;
  }
  if (used == 0) throw Error("precondition: no boundary triangle has a positive size");
  result.mean_affine = mean / used;

  Eigen::Matrix3d affine_map = Eigen::Matrix3d::Identity();
  if (options.affine != AffineMap::none) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(result.mean_affine);
    const Vector3 eigenvalues = solver.eigenvalues();
    if (!(eigenvalues.minCoeff() > 1e-12 * eigenvalues.maxCoeff()))
      throw Error(
          "precondition: the boundary triangles all lie in one plane (mean affine invariant is singular)");
    const Vector3 scales = options.affine == AffineMap::whitening
                               ? eigenvalues.cwiseSqrt().cwiseInverse().eval()
                               : eigenvalues.cwiseInverse().eval();
    affine_map = solver.eigenvectors() * scales.asDiagonal() * solver.eigenvectors().transpose();
  }
  result.forward = affine_map * unshear;
  result.forward /= std::cbrt(result.forward.determinant());  // det F = 1: sizes keep their scale
  result.backward = result.forward.inverse();
  return result;
}

std::vector<Vector3> transform_points(const Eigen::Matrix3d& map, const std::vector<Vector3>& points) {
  std::vector<Vector3> mapped(points.size());
  for (std::size_t point = 0; point < points.size(); ++point) mapped[point] = map * points[point];
  return mapped;
}

void dump_surface(const std::filesystem::path& path, const std::vector<Vector3>& points,
                  const std::vector<std::array<Index, 3>>& triangles) {
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary);
    if (!out) throw file_error(temporary.string(), 0, "cannot open for writing");
    out << std::setprecision(17);
    out << "# vtk DataFile Version 3.0\nmixmesh surface\nASCII\nDATASET POLYDATA\n";
    out << "POINTS " << points.size() << " double\n";
    for (const Vector3& point : points) out << point.x() << ' ' << point.y() << ' ' << point.z() << '\n';
    out << "POLYGONS " << triangles.size() << ' ' << 4 * triangles.size() << '\n';
    for (const auto& triangle : triangles)
      out << "3 " << triangle[0] << ' ' << triangle[1] << ' ' << triangle[2] << '\n';
    if (!out) throw file_error(temporary.string(), 0, "write failed");
  });
}

}  // namespace mixmesh
