#include <algorithm>
#include <cmath>
#include <numeric>

#include "mixmesh/core/error.hpp"
#include "mixmesh/quality/quality.hpp"

namespace mixmesh {

Statistics compute_statistics(std::vector<double> values, int histogram_bins) {
  if (histogram_bins < 1 || histogram_bins > 10000)
    throw Error("histogram bins must lie in [1, 10000], not " + std::to_string(histogram_bins));
  Statistics statistics;
  statistics.histogram.assign(static_cast<std::size_t>(histogram_bins), 0);
  const auto finite_end =
      std::partition(values.begin(), values.end(), [](double value) { return std::isfinite(value); });
  statistics.non_finite = static_cast<std::size_t>(values.end() - finite_end);
  values.erase(finite_end, values.end());
  statistics.count = values.size();
  if (values.empty()) return statistics;

  const auto [lowest, highest] = std::minmax_element(values.begin(), values.end());
  statistics.min = *lowest;
  statistics.max = *highest;
  statistics.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());

  const double width = (statistics.max - statistics.min) / histogram_bins;
  for (double value : values) {
    const double position = width > 0.0 ? (value - statistics.min) / width : 0.0;
    const auto bin = std::min(static_cast<std::size_t>(position), statistics.histogram.size() - 1);
    ++statistics.histogram[bin];
  }

  // Percentiles as numpy's default (linear between the order statistics around
  // q (n − 1)); ascending, so each selection only looks at what lies above the last.
  auto begin = values.begin();
  for (std::size_t slot = 0; slot < statistics_percentiles.size(); ++slot) {
    const double position = statistics_percentiles[slot] / 100.0 * static_cast<double>(values.size() - 1);
    const auto below = static_cast<std::ptrdiff_t>(std::floor(position));
    const auto nth = values.begin() + below;
    std::nth_element(begin, nth, values.end());
    double value = *nth;
    const double fraction = position - static_cast<double>(below);
    if (fraction > 0.0) value += fraction * (*std::min_element(nth + 1, values.end()) - value);
    statistics.percentiles[slot] = value;
    begin = nth;
  }
  return statistics;
}

}  // namespace mixmesh
