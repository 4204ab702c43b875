#include "mixmesh/geometry/airfoil.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include "mixmesh/core/error.hpp"

namespace mixmesh {
namespace {

constexpr int minimum_points_per_surface = 5;

struct Camber {
  double value = 0.0;
  double slope = 0.0;
};

// NACA 4-digit mean line: maximum camber m at chord position p.
Camber four_digit_camber(double x, double m, double p) {
  if (m == 0.0 || p == 0.0) return {};
  if (x < p) return {m / (p * p) * (2.0 * p * x - x * x), 2.0 * m / (p * p) * (p - x)};
  const double q = (1.0 - p) * (1.0 - p);
  return {m / q * (1.0 - 2.0 * p + 2.0 * p * x - x * x), 2.0 * m / q * (p - x)};
}

// NACA 5-digit mean lines (design lift coefficient 0.3; scaled by `scale`). The
// constants m, k1 (and k2/k1 for the reflexed lines) are the published table values.
Camber five_digit_camber(double x, int position, bool reflexed, double scale) {
  static constexpr std::array<std::array<double, 2>, 5> standard = {
      {{0.0580, 361.4}, {0.1260, 51.64}, {0.2025, 15.957}, {0.2900, 6.643}, {0.3910, 3.230}}};
  static constexpr std::array<std::array<double, 3>, 5> reflex = {{{0.0, 0.0, 0.0},
                                                                   {0.1300, 51.99, 0.000764},
                                                                   {0.2170, 15.793, 0.00677},
                                                                   {0.3180, 6.520, 0.0303},
                                                                   {0.4410, 3.191, 0.1355}}};
  const std::size_t row = static_cast<std::size_t>(position - 1);
  if (!reflexed) {
    const double m = standard[row][0];
    const double k1 = standard[row][1];
    if (x < m) {
      return {scale * k1 / 6.0 * (x * x * x - 3.0 * m * x * x + m * m * (3.0 - m) * x),
              scale * k1 / 6.0 * (3.0 * x * x - 6.0 * m * x + m * m * (3.0 - m))};
    }
    return {scale * k1 * m * m * m / 6.0 * (1.0 - x), -scale * k1 * m * m * m / 6.0};
  }
  const double m = reflex[row][0];
  const double k1 = reflex[row][1];
  const double ratio = reflex[row][2];
  const double tail = std::pow(1.0 - m, 3);
  const double m3 = m * m * m;
  if (x < m) {
    return {scale * k1 / 6.0 * (std::pow(x - m, 3) - ratio * tail * x - m3 * x + m3),
            scale * k1 / 6.0 * (3.0 * (x - m) * (x - m) - ratio * tail - m3)};
  }
  return {scale * k1 / 6.0 * (ratio * std::pow(x - m, 3) - ratio * tail * x - m3 * x + m3),
          scale * k1 / 6.0 * (3.0 * ratio * (x - m) * (x - m) - ratio * tail - m3)};
}

// NACA thickness distribution for thickness ratio t.
double naca_thickness(double x, double t, bool closed) {
  const double last = closed ? -0.1036 : -0.1015;
  return 5.0 * t * (0.2969 * std::sqrt(x) + x * (-0.1260 + x * (-0.3516 + x * (0.2843 + x * last))));
}

std::string where(const Airfoil& airfoil, std::size_t point) {
  const long line = point < airfoil.lines.size() ? airfoil.lines[point] : 0;
  return line > 0 ? airfoil.source + ":" + std::to_string(line) : airfoil.source;
}

double orientation(const Vector2& a, const Vector2& b, const Vector2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

bool on_segment(const Vector2& a, const Vector2& b, const Vector2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

bool segments_intersect(const Vector2& a, const Vector2& b, const Vector2& c, const Vector2& d) {
  const double o1 = orientation(a, b, c), o2 = orientation(a, b, d);
  const double o3 = orientation(c, d, a), o4 = orientation(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

double signed_area(const std::vector<Vector2>& points) {
  double twice = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vector2& a = points[k];
    const Vector2& b = points[(k + 1) % points.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

// Splits a line into numbers; false if a field is not a number.
bool parse_numbers(const std::string& line, std::vector<double>& numbers) {
  numbers.clear();
  std::istringstream stream(line);
  std::string field;
  while (stream >> field) {
    char* end = nullptr;
    const double value = std::strtod(field.c_str(), &end);
    if (end == field.c_str() || *end != '\0' || !std::isfinite(value)) return false;
    numbers.push_back(value);
  }
  return true;
}

struct NumberedLine {
  long line;
  std::vector<double> numbers;
};

}  // namespace

Airfoil naca_airfoil(const std::string& designation, const NacaOptions& options) {
  std::string digits;
  for (char character : designation) {
    if (!std::isspace(static_cast<unsigned char>(character)) && character != '-') digits += character;
  }
  if (digits.size() > 4 && (digits.rfind("NACA", 0) == 0 || digits.rfind("naca", 0) == 0)) digits.erase(0, 4);
  const bool numeric = !digits.empty() && std::all_of(digits.begin(), digits.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
  });
  if (!numeric || (digits.size() != 4 && digits.size() != 5)) {
    throw Error("NACA designation '" + designation + "': expected 4 or 5 digits, e.g. 0012, 2412, 23012");
  }
  if (options.points_per_side < minimum_points_per_surface) {
    throw Error("NACA " + digits + ": points_per_side must be at least " +
                std::to_string(minimum_points_per_surface));
  }
  const auto digit = [&](std::size_t position) { return digits[position] - '0'; };
  const double thickness = std::stod(digits.substr(digits.size() - 2)) / 100.0;
  if (thickness <= 0.0) throw Error("NACA " + digits + ": thickness must be positive");
  std::function<Camber(double)> camber;
  if (digits.size() == 4) {
    const double m = digit(0) / 100.0, p = digit(1) / 10.0;
    if ((m == 0.0) != (p == 0.0)) {
      throw Error("NACA " + digits + ": camber and its position must both be zero or both non-zero");
    }
    camber = [m, p](double x) { return four_digit_camber(x, m, p); };
  } else {
    const int lift = digit(0), position = digit(1), reflex = digit(2);
    const bool valid =
        lift > 0 && position >= 1 && position <= 5 && (reflex == 0 || (reflex == 1 && position >= 2));
    if (!valid) throw Error("NACA " + digits + ": no such 5-digit mean line (L P S = 1-9, 1-5, 0 or 1)");
    camber = [=](double x) { return five_digit_camber(x, position, reflex == 1, lift / 2.0); };
  }

  Airfoil airfoil;
  airfoil.source = "NACA " + digits;
  const int count = options.points_per_side;
  std::vector<Vector2> upper, lower;
  for (int k = 0; k < count; ++k) {
    const double x = 0.5 * (1.0 - std::cos(M_PI * k / (count - 1)));  // cosine spacing
    double half = naca_thickness(x, thickness, options.closed_trailing_edge);
    if (k == count - 1 && options.closed_trailing_edge) half = 0.0;
    const Camber mean = camber(x);
    const double angle = std::atan(mean.slope);
    upper.emplace_back(x - half * std::sin(angle), mean.value + half * std::cos(angle));
    lower.emplace_back(x + half * std::sin(angle), mean.value - half * std::cos(angle));
  }
  for (int k = count - 1; k >= 0; --k) airfoil.points.push_back(lower[static_cast<std::size_t>(k)]);
  airfoil.leading_edge = static_cast<std::size_t>(count - 1);
  for (int k = 1; k < count; ++k) airfoil.points.push_back(upper[static_cast<std::size_t>(k)]);
  airfoil.lines.assign(airfoil.points.size(), 0);
  validate_airfoil(airfoil);
  return airfoil;
}

Airfoil read_airfoil_file(const std::filesystem::path& path) {
  std::ifstream stream(path);
  if (!stream) throw file_error(path.string(), 0, "cannot open the airfoil file");
  std::vector<NumberedLine> rows;
  std::string text;
  long line = 0;
  bool first_content = true;
  std::vector<double> numbers;
  std::vector<long> blank_after;  // data row counts at each blank line (Lednicer layout)
  while (std::getline(stream, text)) {
    ++line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.find_first_not_of(" \t") == std::string::npos) {
      blank_after.push_back(static_cast<long>(rows.size()));
      continue;
    }
    const bool parsed = parse_numbers(text, numbers);
    if (first_content) {
      first_content = false;
      if (!parsed || numbers.size() != 2) continue;  // the name line
    }
    if (!parsed || numbers.size() != 2) {
      throw file_error(path.string(), line, "expected two numbers (x z), got '" + text + "'");
    }
    rows.push_back({line, numbers});
  }
  if (stream.bad()) throw file_error(path.string(), line, "read error");
  if (rows.empty()) throw file_error(path.string(), line, "no coordinates in the airfoil file");

  Airfoil raw;
  raw.source = path.string();
  const double first_a = rows[0].numbers[0], first_b = rows[0].numbers[1];
  const bool lednicer = first_a >= 2.0 && first_b >= 2.0;
  if (lednicer) {
    if (first_a != std::floor(first_a) || first_b != std::floor(first_b)) {
      throw file_error(path.string(), rows[0].line, "Lednicer point counts must be whole numbers");
    }
    const std::size_t upper_count = static_cast<std::size_t>(first_a);
    const std::size_t lower_count = static_cast<std::size_t>(first_b);
    if (rows.size() - 1 != upper_count + lower_count) {
      throw file_error(path.string(), rows[0].line,
                       "Lednicer header announces " + std::to_string(upper_count) + " + " +
                           std::to_string(lower_count) + " points, the file has " +
                           std::to_string(rows.size() - 1));
    }
    // Lower from the trailing edge to the leading edge, then upper from the leading edge.
    for (std::size_t k = upper_count + lower_count; k > upper_count; --k) {
      raw.points.emplace_back(rows[k].numbers[0], rows[k].numbers[1]);
      raw.lines.push_back(rows[k].line);
    }
    const std::size_t skip =
        (raw.points.back() - Vector2(rows[1].numbers[0], rows[1].numbers[1])).norm() == 0.0;
    for (std::size_t k = 1 + skip; k <= upper_count; ++k) {
      raw.points.emplace_back(rows[k].numbers[0], rows[k].numbers[1]);
      raw.lines.push_back(rows[k].line);
    }
  } else {
    for (const NumberedLine& row : rows) {
      raw.points.emplace_back(row.numbers[0], row.numbers[1]);
      raw.lines.push_back(row.line);
    }
  }
  return normalise_airfoil(std::move(raw));
}

Airfoil normalise_airfoil(Airfoil raw) {
  // Consecutive duplicates (e.g. a repeated leading-edge point) carry no shape.
  Airfoil airfoil;
  airfoil.source = raw.source;
  for (std::size_t k = 0; k < raw.points.size(); ++k) {
    if (!airfoil.points.empty() && (raw.points[k] - airfoil.points.back()).norm() == 0.0) continue;
    airfoil.points.push_back(raw.points[k]);
    airfoil.lines.push_back(k < raw.lines.size() ? raw.lines[k] : 0);
  }
  if (airfoil.points.size() < 2 * minimum_points_per_surface - 1) {
    throw Error(airfoil.source + ": too few points (" + std::to_string(airfoil.points.size()) +
                "), an airfoil needs at least " + std::to_string(minimum_points_per_surface) +
                " per surface");
  }
  const Vector2 trailing_edge = 0.5 * (airfoil.points.front() + airfoil.points.back());
  std::size_t leading_edge = 0;
  for (std::size_t k = 0; k < airfoil.points.size(); ++k) {
    if ((airfoil.points[k] - trailing_edge).norm() > (airfoil.points[leading_edge] - trailing_edge).norm()) {
      leading_edge = k;
    }
  }
  const Vector2 chord = trailing_edge - airfoil.points[leading_edge];
  const double length = chord.norm();
  const double cosine = chord.x() / length, sine = chord.y() / length;
  const Vector2 origin = airfoil.points[leading_edge];
  for (Vector2& point : airfoil.points) {
    const Vector2 shifted = (point - origin) / length;
    point = Vector2(cosine * shifted.x() + sine * shifted.y(), -sine * shifted.x() + cosine * shifted.y());
  }
  airfoil.points[leading_edge] = Vector2::Zero();
  airfoil.leading_edge = leading_edge;
  // Lower surface first means a clockwise outline in the (x, z) plane.
  if (signed_area(airfoil.points) > 0.0) {
    std::reverse(airfoil.points.begin(), airfoil.points.end());
    std::reverse(airfoil.lines.begin(), airfoil.lines.end());
    airfoil.leading_edge = airfoil.points.size() - 1 - leading_edge;
  }
  // A trailing-edge gap at round-off level is a sharp trailing edge.
  if (airfoil.trailing_edge_gap() < 1e-9) {
    airfoil.points.front() = Vector2(1.0, 0.0);
    airfoil.points.back() = Vector2(1.0, 0.0);
  }
  validate_airfoil(airfoil);
  return airfoil;
}

void validate_airfoil(const Airfoil& airfoil) {
  const std::size_t count = airfoil.points.size();
  const std::size_t lower = airfoil.leading_edge + 1;
  const std::size_t upper = count - airfoil.leading_edge;
  if (lower < minimum_points_per_surface || upper < minimum_points_per_surface) {
    throw Error(where(airfoil, airfoil.leading_edge) + ": too few points: " + std::to_string(lower) +
                " on one surface and " + std::to_string(upper) + " on the other (at least " +
                std::to_string(minimum_points_per_surface) + " each, leading edge included)");
  }
  for (std::size_t k = 1; k < count; ++k) {
    if ((airfoil.points[k] - airfoil.points[k - 1]).norm() == 0.0) {
      throw Error(where(airfoil, k) + ": point repeats the previous one");
    }
  }
  // The outline (closed across a blunt trailing edge) must be a simple polygon: any
  // crossing of two non-adjacent segments means the surfaces cross or fold.
  const bool sharp = airfoil.trailing_edge_gap() == 0.0;
  const std::size_t segments = sharp ? count - 1 : count;
  for (std::size_t a = 0; a < segments; ++a) {
    for (std::size_t b = a + 2; b < segments; ++b) {
      if (a == 0 && b == segments - 1) continue;  // they meet at the trailing edge
      const Vector2& p = airfoil.points[a];
      const Vector2& q = airfoil.points[(a + 1) % count];
      const Vector2& r = airfoil.points[b];
      const Vector2& s = airfoil.points[(b + 1) % count];
      if (segments_intersect(p, q, r, s)) {
        const long other = a < airfoil.lines.size() ? airfoil.lines[a] : 0;
        throw Error(where(airfoil, b) +
                    ": the upper and lower surfaces cross (the segment at this point meets " +
                    (other > 0 ? "the one at line " + std::to_string(other) : "another") + ")");
      }
    }
  }
}

Airfoil close_trailing_edge(const Airfoil& airfoil) {
  Airfoil closed = airfoil;
  const Vector2 middle = 0.5 * (airfoil.points.front() + airfoil.points.back());
  const Vector2 lower_shift = middle - airfoil.points.front();
  const Vector2 upper_shift = middle - airfoil.points.back();
  for (std::size_t k = 0; k < closed.points.size(); ++k) {
    const double weight = std::clamp(airfoil.points[k].x(), 0.0, 1.0);
    closed.points[k] += weight * (k <= airfoil.leading_edge ? lower_shift : upper_shift);
  }
  closed.points.front() = middle;
  closed.points.back() = middle;
  validate_airfoil(closed);
  return closed;
}

double section_area(const Airfoil& airfoil) {
  return std::abs(signed_area(airfoil.points));
}

}  // namespace mixmesh
