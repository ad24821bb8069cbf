#include "scene/values.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace rtsph::scene_detail {

std::string format_number(double v) { return fmt::format("{}", v); }

std::string format_vec(const Vec3d& v, int dimension) {
  std::string s = "[";
  for (int i = 0; i < dimension; ++i) s += (i ? ", " : "") + format_number(v[i]);
  return s + "]";
}

std::string format_range(const ParamMeta& m) {
  return fmt::format("{}{}, {}]", m.min_exclusive ? "(" : "[", format_number(m.min),
                     format_number(m.max));
}

std::string expected_text(const ParamMeta& m, int dimension) {
  const std::string unit = m.unit.empty() ? "" : fmt::format(" ({})", m.unit);
  switch (m.kind) {
    case ParamKind::Real: return fmt::format("expected a number in {}{}", format_range(m), unit);
    case ParamKind::Int: return fmt::format("expected an integer in {}{}", format_range(m), unit);
    case ParamKind::Bool: return "expected true or false";
    case ParamKind::String: return "expected a non-empty string";
    case ParamKind::Vec3:
      if (m.z_only_in_2d && dimension == 2)
        return fmt::format("expected a number in {}{} (about z in 2D)", format_range(m), unit);
      return fmt::format("expected an array of {} numbers (dimension {}), each in {}{}", dimension,
                         dimension, format_range(m), unit);
    case ParamKind::Enum: break;
  }
  std::string list;
  for (const auto& c : m.choices_for(dimension)) list += (list.empty() ? "\"" : ", \"") + c + "\"";
  const bool differs = !m.choices_2d.empty();
  return fmt::format("expected one of {}{}", list,
                     differs ? fmt::format(" (in a {}D scene)", dimension) : "");
}

bool number_fits(const ParamMeta& m, double v) {
  if (!std::isfinite(v)) return false;
  if (m.kind == ParamKind::Int && v != std::floor(v)) return false;
  const bool above_min = m.min_exclusive ? v > m.min : v >= m.min;
  return above_min && v <= m.max;
}

int choice_index(const ParamMeta& m, std::string_view name, int dimension) {
  const auto& list = m.choices_for(dimension);
  const auto it = std::find(list.begin(), list.end(), name);
  return it == list.end() ? -1 : int(it - list.begin());
}

namespace {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string nearest_key(std::string_view key, const std::vector<std::string>& candidates) {
  // Long garbage keys would make the O(n·m) distance slow under fuzzing; no key is this long.
  if (key.size() > 200) return {};
  std::string best;
  std::size_t best_d = std::max<std::size_t>(3, key.size() / 3) + 1;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(key, c);
    if (d < best_d) best_d = d, best = c;
  }
  return best;
}

}  // namespace rtsph::scene_detail
