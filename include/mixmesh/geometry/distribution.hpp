// Point distributions on [0, 1]: where the nodes of a line of `cells` intervals go.
//
//   positions   cells + 1 increasing values, positions[0] = 0, positions[cells] = 1
//
// Spacings are fractions of the line's length. The Vinokur distributions hit the
// requested end spacings exactly (to 1e-9 relative): Vinokur's closed form fixes the
// end derivatives, and a short fixed-point loop corrects its input spacings until
// the first and last discrete intervals match.
#pragma once

#include <vector>

namespace mixmesh {

std::vector<double> uniform_distribution(int cells);

// Two-sided stretching with first and last spacing (Vinokur, J. Comput. Phys. 50,
// 1983, eqs. for the tanh / tan stretching functions). A spacing <= 0 leaves that end
// free (one-sided stretching). Throws mixmesh::Error when the spacings cannot fit.
std::vector<double> vinokur_distribution(int cells, double first_spacing, double last_spacing);

// Geometric growth from first_spacing by `growth` per cell until the line reaches 1;
// the last, partial cell is absorbed by scaling the whole progression. Returns the
// positions (cell count follows from the spacing and the growth).
std::vector<double> geometric_distribution(double first_spacing, double growth);

}  // namespace mixmesh
