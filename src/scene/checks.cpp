#include "scene/checks.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>

#include "scene/scene_error.h"
#include "core/kernels.h"
#include "scene/values.h"
#include "solvers/simulation.h"

namespace rtsph::scene_detail {
namespace {

class Checker {
 public:
  Checker(const SimSpec& s, const std::string& source) : s_(s), source_(source), d_(s.dimension) {
    double extent = 0;
    for (int i = 0; i < d_; ++i) extent = std::max(extent, s.domain_max[i] - s.domain_min[i]);
    eps_ = 1e-9 * std::max(extent, 1.0);  // lets geometry touch the walls despite rounding
  }

  [[noreturn]] void fail(const std::string& path, const std::string& value,
                         const std::string& expected) const {
    throw SceneError(source_, path, value, expected);
  }
  std::string vec(const Vec3d& v) const { return format_vec(v, d_); }
  std::string domain() const {
    return fmt::format("the domain {} to {}", vec(s_.domain_min), vec(s_.domain_max));
  }
  bool inside(const Vec3d& p) const {
    for (int i = 0; i < d_; ++i)
      if (p[i] < s_.domain_min[i] - eps_ || p[i] > s_.domain_max[i] + eps_) return false;
    return true;
  }
  void require_inside(const std::string& path, const Vec3d& p) const {
    if (!inside(p)) fail(path, vec(p), "expected a point inside " + domain());
  }
  void require_less(const std::string& min_key, const Vec3d& lo, const std::string& max_key,
                    const Vec3d& hi) const {
    for (int i = 0; i < d_; ++i)
      if (!(lo[i] < hi[i]))
        fail(max_key, vec(hi), fmt::format("expected every component greater than {} {}", min_key, vec(lo)));
  }

  void domain_and_spacing() const {
    require_less("domain.min", s_.domain_min, "domain.max", s_.domain_max);
    for (int i = 0; i < d_; ++i)
      if (2 * s_.spacing > s_.domain_max[i] - s_.domain_min[i])
        fail("fluid.spacing", format_number(s_.spacing),
             fmt::format("expected at most half the smallest extent of {}", domain()));
  }

  // A periodic extent holds whole lattice cells, or the seam would be a gap or an overlap in
  // the fluid and the wall samples; and three kernel supports, or the neighbour grid could not
  // tell a particle's images apart.
  void periodic_axes() const {
    static const char* kAxis = "xyz";
    if (d_ == 2 && axis_is_periodic(s_.periodic, 2))
      fail("domain.periodic", fmt::format("\"{}\"", periodic_name()), "expected none, x, y or xy in a 2D scene");
    const double support = double(support_ratio(s_.kernel)) * s_.smoothing_ratio * s_.spacing;
    for (int k = 0; k < d_; ++k) {
      if (!axis_is_periodic(s_.periodic, k)) continue;
      const double extent = s_.domain_max[k] - s_.domain_min[k];
      const double cells = extent / s_.spacing;
      if (std::abs(cells - std::round(cells)) > 1e-6 * std::max(1.0, cells))
        fail("domain.periodic", fmt::format("\"{}\"", periodic_name()),
             fmt::format("expected the periodic {} extent {} m to be a whole number of fluid.spacing = {} m",
                         kAxis[k], format_number(extent), format_number(s_.spacing)));
      if (extent < 3 * support * (1 + 1e-4))
        fail("domain.periodic", fmt::format("\"{}\"", periodic_name()),
             fmt::format("expected the periodic {} extent {} m to be at least three kernel supports ({} m)",
                         kAxis[k], format_number(extent), format_number(3 * support * (1 + 1e-4))));
    }
  }
  std::string periodic_name() const {
    std::string n;
    for (int k = 0; k < 3; ++k)
      if (axis_is_periodic(s_.periodic, k)) n += "xyz"[k];
    return n.empty() ? "none" : n;
  }

  void blocks() const {
    for (std::size_t i = 0; i < s_.fluid_blocks.size(); ++i) {
      const auto& b = s_.fluid_blocks[i];
      const std::string p = fmt::format("fluid_blocks[{}].", i);
      require_less(p + "min", b.min, p + "max", b.max);
      require_inside(p + "min", b.min);
      require_inside(p + "max", b.max);
      for (int k = 0; k < d_; ++k)
        if (b.max[k] - b.min[k] < s_.spacing - eps_)
          fail(p + "max", vec(b.max),
               fmt::format("expected the block at least fluid.spacing = {} m thick (it would hold "
                           "no particles)", format_number(s_.spacing)));
    }
  }

  void obstacles() const {
    for (std::size_t i = 0; i < s_.obstacles.size(); ++i) {
      const auto& o = s_.obstacles[i];
      const std::string p = fmt::format("obstacles[{}].", i);
      require_inside(p + "center", o.center);
      if (o.motion == MotionKind::Path && o.path.empty())
        fail(p + "motion.keyframes", "[]", "expected at least one keyframe for a path motion");
      for (std::size_t k = 0; k < o.path.size(); ++k) {
        const std::string kp = fmt::format("{}motion.keyframes[{}].", p, k);
        require_inside(kp + "position", o.path[k].position);
        if (k > 0 && !(o.path[k].time_s > o.path[k - 1].time_s))
          fail(kp + "time", format_number(o.path[k].time_s),
               fmt::format("expected a time after the previous keyframe's {} s",
                           format_number(o.path[k - 1].time_s)));
      }
    }
  }

  void emitters() const {
    for (std::size_t i = 0; i < s_.emitters.size(); ++i) {
      const auto& e = s_.emitters[i];
      const std::string p = fmt::format("emitters[{}].", i);
      require_inside(p + "position", e.position);
      double len2 = 0;
      for (int k = 0; k < d_; ++k) len2 += e.direction[k] * e.direction[k];
      if (!(len2 > 0)) fail(p + "direction", vec(e.direction), "expected a non-zero vector");
      if (!(e.stop_s > e.start_s))
        fail(p + "stop", format_number(e.stop_s),
             fmt::format("expected a time after start = {} s", format_number(e.start_s)));
      if (e.width < s_.spacing - eps_)
        fail(p + "width", format_number(e.width),
             fmt::format("expected at least fluid.spacing = {} m", format_number(s_.spacing)));
    }
  }

 private:
  const SimSpec& s_;
  const std::string& source_;
  int d_;
  double eps_ = 0;
};

}  // namespace

void check_geometry(const SimSpec& spec, const std::string& source) {
  const Checker c(spec, source);
  c.domain_and_spacing();
  c.periodic_axes();
  c.blocks();
  c.obstacles();
  c.emitters();
}

void check_memory(const SimSpec& spec, const std::string& source, std::size_t available) {
  const std::size_t bytes = estimate_memory_bytes(spec);
  if (bytes > available)
    throw SceneError(source, "fluid.spacing", format_number(spec.spacing),
                     fmt::format("the scene needs about {} bytes ({:.3g} GiB) but this machine has "
                                 "{} bytes ({:.3g} GiB) of physical memory; increase the spacing",
                                 bytes, double(bytes) / (1 << 30), available,
                                 double(available) / (1 << 30)));
}

std::size_t physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return std::size_t(-1);  // unknown: do not refuse anything
  return std::size_t(pages) * std::size_t(page);
}

}  // namespace rtsph::scene_detail
