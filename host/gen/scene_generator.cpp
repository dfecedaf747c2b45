#include "host/gen/scene_generator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

namespace evms::gen {
namespace {

struct Vec {
  double x = 0, y = 0;
  Vec operator+(Vec o) const { return {x + o.x, y + o.y}; }
  Vec operator-(Vec o) const { return {x - o.x, y - o.y}; }
  Vec operator*(double s) const { return {x * s, y * s}; }
  double dot(Vec o) const { return x * o.x + y * o.y; }
  double norm() const { return std::hypot(x, y); }
};

Vec rotate(Vec v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}

// A shape in its own frame, centred on its geometric centre. Signed distance is negative
// inside. Polygons are exact; the ellipse is the usual first-order approximation, which only
// shapes the one-pixel anti-aliasing ramp.
struct Shape {
  enum class Kind { kCircle, kEllipse, kPolygon } kind;
  std::string name;
  double a = 0, b = 0;            // radius, or ellipse half-axes
  std::vector<Vec> vertices;      // polygon, counter-clockwise
  double bound = 0;               // radius of a circle that holds the shape

  double sdf(Vec p) const {
    switch (kind) {
      case Kind::kCircle: return p.norm() - a;
      case Kind::kEllipse: {
        const double k = std::hypot(p.x / a, p.y / b);
        return (k - 1.0) * std::min(a, b);
      }
      case Kind::kPolygon: break;
    }
    double d2 = 1e300;
    bool inside = false;
    for (size_t i = 0, j = vertices.size() - 1; i < vertices.size(); j = i++) {
      const Vec vi = vertices[i], vj = vertices[j];
      const Vec e = vj - vi, w = p - vi;
      const double h = std::clamp(w.dot(e) / e.dot(e), 0.0, 1.0);
      const Vec d = w - e * h;
      d2 = std::min(d2, d.dot(d));
      if ((vi.y > p.y) != (vj.y > p.y) && p.x < (vj.x - vi.x) * (p.y - vi.y) / (vj.y - vi.y) + vi.x) {
        inside = !inside;
      }
    }
    return inside ? -std::sqrt(d2) : std::sqrt(d2);
  }
};

Shape circle(double r) { return {Shape::Kind::kCircle, "circle", r, r, {}, r}; }
Shape ellipse(double a, double b) { return {Shape::Kind::kEllipse, "ellipse", a, b, {}, std::max(a, b)}; }
Shape polygon(std::string name, std::vector<Vec> v) {
  double bound = 0;
  for (Vec p : v) bound = std::max(bound, p.norm());
  return {Shape::Kind::kPolygon, std::move(name), 0, 0, std::move(v), bound};
}
Shape regular(std::string name, int n, double r, double phase = M_PI / 2) {
  std::vector<Vec> v;
  for (int i = 0; i < n; ++i) v.push_back(rotate({r, 0}, phase + 2 * M_PI * i / n));
  return polygon(std::move(name), std::move(v));
}
Shape star(double r_out, double r_in) {
  std::vector<Vec> v;
  for (int i = 0; i < 10; ++i) v.push_back(rotate({i % 2 ? r_in : r_out, 0}, M_PI / 2 + M_PI * i / 5));
  return polygon("star", std::move(v));
}
Shape box(std::string name, double hx, double hy) {
  return polygon(std::move(name), {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}});
}

struct Object {
  Shape shape;
  Vec home;           // poster position of the centre
  double angle;       // orientation on the poster
  double intensity;   // reflectance on a white (1.0) poster
  bool mover = false; // slides across the poster
  Vec slide;          // displacement amplitude of a mover
  double slide_hz = 0;
  double slide_phase = 0;
};

}  // namespace

bool parse_motion(const std::string& name, Motion& out) {
  if (name == "translation") out = Motion::kTranslation;
  else if (name == "rotation") out = Motion::kRotation;
  else if (name == "6dof") out = Motion::kSixDof;
  else return false;
  return true;
}

const char* motion_name(Motion m) {
  switch (m) {
    case Motion::kTranslation: return "translation";
    case Motion::kRotation: return "rotation";
    case Motion::kSixDof: return "6dof";
  }
  return "?";
}

struct SceneGenerator::Impl {
  SceneConfig cfg;
  Random rng;
  std::vector<Object> objects;
  Vec centre;           // sensor centre, px
  double motion_phase[4];

  // Per-pixel sensor state.
  std::vector<double> log_ref, log_prev, th_on, th_off;
  std::vector<TimeUs> last_fire;
  std::vector<std::int8_t> owner;
  std::vector<std::uint32_t> visited;
  std::uint32_t step = 0;

  double t_s = 0;                  // simulated time reached, s
  double next_noise_s = 0;
  TimeUs next_truth_us = 0;
  std::vector<LabelledEvent> pending;  // generated, not yet released (jitter reordering)
  bool done = false;

  explicit Impl(const SceneConfig& c) : cfg(c), rng(c.seed) {
    centre = {(cfg.width - 1) / 2.0, (cfg.height - 1) / 2.0};
    build_poster();
    for (double& p : motion_phase) p = rng.uniform(0, 2 * M_PI);
    const size_t n = static_cast<size_t>(cfg.width) * cfg.height;
    log_ref.resize(n);
    log_prev.resize(n);
    th_on.resize(n);
    th_off.resize(n);
    last_fire.assign(n, INT64_MIN / 2);
    owner.assign(n, -1);
    visited.assign(n, 0);
    for (size_t i = 0; i < n; ++i) {
      th_on[i] = std::max(0.05, cfg.contrast_threshold + cfg.threshold_sigma * rng.normal());
      th_off[i] = std::max(0.05, cfg.contrast_threshold + cfg.threshold_sigma * rng.normal());
    }
    for (int y = 0; y < cfg.height; ++y) {
      for (int x = 0; x < cfg.width; ++x) {
        int who = -1;
        const double l = std::log(intensity(x, y, 0.0, who));
        const size_t i = index(x, y);
        log_ref[i] = log_prev[i] = l;
        owner[i] = static_cast<std::int8_t>(who);
      }
    }
    next_noise_s = cfg.noise_hz > 0 ? rng.exponential(cfg.noise_hz * n) : 1e300;
  }

  size_t index(int x, int y) const { return static_cast<size_t>(y) * cfg.width + x; }

  // Nine shapes on a jittered 3x3 grid that spans more than the field of view, with random
  // size, orientation and contrast. Two of them slide in front of their neighbours.
  void build_poster() {
    const double sx = cfg.width / 240.0, sy = cfg.height / 180.0;
    const double s = std::min(sx, sy);
    std::vector<Shape> shapes = {
        circle(15 * s),           ellipse(19 * s, 11 * s),     regular("triangle", 3, 19 * s),
        box("square", 13 * s, 13 * s), box("rectangle", 20 * s, 10 * s), regular("pentagon", 5, 16 * s),
        regular("hexagon", 6, 16 * s), star(19 * s, 8 * s),      regular("diamond", 4, 17 * s, 0),
    };
    // Shuffle which shape sits where.
    for (size_t i = shapes.size() - 1; i > 0; --i) std::swap(shapes[i], shapes[rng.below(i + 1)]);
    for (int gy = 0; gy < 3; ++gy) {
      for (int gx = 0; gx < 3; ++gx) {
        Object o{shapes[static_cast<size_t>(gy * 3 + gx)], {}, 0, 0, false, {}, 0, 0};
        const double size_scale = rng.uniform(0.85, 1.15);
        for (Vec& v : o.shape.vertices) v = v * size_scale;
        o.shape.a *= size_scale;
        o.shape.b *= size_scale;
        o.shape.bound *= size_scale;
        o.home = {cfg.width * (0.5 + (gx - 1) * 0.36) + rng.uniform(-7, 7) * sx,
                  cfg.height * (0.5 + (gy - 1) * 0.36) + rng.uniform(-6, 6) * sy};
        o.angle = rng.uniform(0, 2 * M_PI);
        o.intensity = rng.uniform(0.04, 0.35);
        objects.push_back(std::move(o));
      }
    }
    // Movers: the centre-row outer shapes slide towards (and over) the middle one, and the
    // top-middle one slides down over it. Drawn last, so they are in front.
    const int mover_index[2] = {3, 1};
    const Vec slide_dir[2] = {{0.36 * cfg.width * 0.9, 0}, {0, 0.36 * cfg.height * 0.9}};
    for (int m = 0; m < 2; ++m) {
      Object& o = objects[static_cast<size_t>(mover_index[m])];
      o.mover = true;
      o.slide = slide_dir[m];
      o.slide_hz = rng.uniform(0.15, 0.25);
      o.slide_phase = rng.uniform(0, 2 * M_PI);
    }
    std::stable_partition(objects.begin(), objects.end(), [](const Object& o) { return !o.mover; });
  }

  // Camera pose at motion time u (s): poster point of a sensor pixel p is
  //   R(theta) * (p - c) * zoom + c + d.
  struct Pose {
    Vec d;
    double theta = 0, zoom = 1;
  };
  Pose pose(double t) const {
    const double u = t * cfg.speed;
    const double* ph = motion_phase;
    const double w = cfg.width / 240.0;
    Pose p;
    switch (cfg.motion) {
      case Motion::kTranslation:
        p.d = {45 * w * std::sin(2 * M_PI * 0.45 * u + ph[0]), 32 * w * std::sin(2 * M_PI * 0.31 * u + ph[1])};
        break;
      case Motion::kRotation:
        p.theta = 0.75 * std::sin(2 * M_PI * 0.30 * u + ph[2]);
        p.d = {6 * w * std::sin(2 * M_PI * 0.2 * u + ph[0]), 5 * w * std::sin(2 * M_PI * 0.17 * u + ph[1])};
        break;
      case Motion::kSixDof:
        p.d = {30 * w * std::sin(2 * M_PI * 0.37 * u + ph[0]), 22 * w * std::sin(2 * M_PI * 0.29 * u + ph[1])};
        p.theta = 0.35 * std::sin(2 * M_PI * 0.23 * u + ph[2]);
        p.zoom = std::exp(0.22 * std::sin(2 * M_PI * 0.21 * u + ph[3]));
        break;
    }
    return p;
  }
  Vec to_poster(Vec pix, const Pose& p) const { return rotate(pix - centre, p.theta) * p.zoom + centre + p.d; }
  Vec to_pixel(Vec poster, const Pose& p) const { return rotate(poster - centre - p.d, -p.theta) * (1.0 / p.zoom) + centre; }

  Vec object_centre(const Object& o, double t) const {
    if (!o.mover) return o.home;
    return o.home + o.slide * std::sin(2 * M_PI * o.slide_hz * t * cfg.speed + o.slide_phase);
  }

  // Intensity seen by pixel (x, y) at time t, and the topmost object covering it.
  double intensity(int x, int y, double t, int& who) const { return intensity(x, y, pose(t), t, who); }
  double intensity(int x, int y, const Pose& p, double t, int& who) const {
    const Vec q = to_poster({double(x), double(y)}, p);
    double value = 1.0;
    who = -1;
    for (size_t k = 0; k < objects.size(); ++k) {
      const Object& o = objects[k];
      const Vec rel = q - object_centre(o, t);
      if (rel.norm() > o.shape.bound + 2 * p.zoom) continue;
      const double d = o.shape.sdf(rotate(rel, -o.angle)) / p.zoom;  // in pixels
      const double cover = std::clamp(0.5 - d, 0.0, 1.0);
      if (cover > 0) {
        value = value * (1 - cover) + o.intensity * cover;
        if (cover > 0.02) who = static_cast<int>(k);
      }
    }
    return value;
  }

  // The largest pixel displacement per second of any object, to choose the time step.
  double pixel_speed(double t) const {
    const double h = 1e-3;
    const Pose a = pose(t), b = pose(t + h);
    double v = 0;
    for (const Object& o : objects) {
      const Vec pa = to_pixel(object_centre(o, t), a), pb = to_pixel(object_centre(o, t + h), b);
      // Rotation and zoom move the rim faster than the centre.
      const double rim = o.shape.bound / a.zoom * (std::abs(b.theta - a.theta) + std::abs(std::log(b.zoom / a.zoom)));
      v = std::max(v, ((pb - pa).norm() + rim) / h);
    }
    return v;
  }

  void emit(double t_event_s, int x, int y, bool on, int label) {
    const size_t i = index(x, y);
    const TimeUs t = static_cast<TimeUs>(std::llround(t_event_s * 1e6));
    if (t - last_fire[i] < cfg.refractory_us) return;
    last_fire[i] = t;
    const TimeUs jittered = std::max<TimeUs>(0, t + static_cast<TimeUs>(std::llround(cfg.jitter_us * rng.normal())));
    pending.push_back({{jittered, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), static_cast<std::uint8_t>(on)}, label});
  }

  // Advances the simulation by one step.
  void advance(std::vector<TruthSample>& truth) {
    const double end = cfg.duration_s;
    const double v = pixel_speed(t_s);
    const double dt = std::clamp(0.25 / std::max(v, 1e-9), 20e-6, 2e-3);
    const double t1 = std::min(t_s + dt, end);
    const Pose p0 = pose(t_s), p1 = pose(t1);
    ++step;

    // Only pixels near an object can change.
    for (const Object& o : objects) {
      const Vec c0 = to_pixel(object_centre(o, t_s), p0), c1 = to_pixel(object_centre(o, t1), p1);
      const double r = o.shape.bound / std::min(p0.zoom, p1.zoom) + 2.5;
      const int x0 = std::max(0, int(std::floor(std::min(c0.x, c1.x) - r)));
      const int x1 = std::min(cfg.width - 1, int(std::ceil(std::max(c0.x, c1.x) + r)));
      const int y0 = std::max(0, int(std::floor(std::min(c0.y, c1.y) - r)));
      const int y1 = std::min(cfg.height - 1, int(std::ceil(std::max(c0.y, c1.y) + r)));
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          const size_t i = index(x, y);
          if (visited[i] == step) continue;
          visited[i] = step;
          int who = -1;
          const double l1 = std::log(intensity(x, y, p1, t1, who));
          const double l0 = log_prev[i];
          const int label = who >= 0 ? who : owner[i];
          if (l1 != l0) crossings(x, y, l0, l1, t_s, t1, label);
          log_prev[i] = l1;
          owner[i] = static_cast<std::int8_t>(who);
        }
      }
    }

    while (next_noise_s <= t1) {
      const auto pixel = rng.below(static_cast<std::uint64_t>(cfg.width) * cfg.height);
      emit(next_noise_s, int(pixel % cfg.width), int(pixel / cfg.width), rng.uniform() < 0.5, kNoiseLabel);
      next_noise_s += rng.exponential(cfg.noise_hz * cfg.width * cfg.height);
    }

    while (next_truth_us <= static_cast<TimeUs>(t1 * 1e6)) {
      const double t = next_truth_us * 1e-6;
      const Pose p = pose(t);
      for (size_t k = 0; k < objects.size(); ++k) {
        const Vec c = to_pixel(object_centre(objects[k], t), p);
        const double r = objects[k].shape.bound / p.zoom;
        if (c.x - r >= 0 && c.y - r >= 0 && c.x + r <= cfg.width - 1 && c.y + r <= cfg.height - 1) {
          truth.push_back({next_truth_us, static_cast<int>(k), c.x, c.y, r});
        }
      }
      next_truth_us += 1000;
    }
    t_s = t1;
  }

  // Events for the log-intensity change l0 -> l1 of one pixel over [ta, tb], one per
  // threshold crossed, at the linearly interpolated crossing times.
  void crossings(int x, int y, double l0, double l1, double ta, double tb, int label) {
    const size_t i = index(x, y);
    double& ref = log_ref[i];
    for (;;) {
      double level;
      bool on;
      if (l1 - ref >= th_on[i]) {
        level = ref + th_on[i];
        on = true;
      } else if (ref - l1 >= th_off[i]) {
        level = ref - th_off[i];
        on = false;
      } else {
        return;
      }
      const double f = std::clamp((level - l0) / (l1 - l0), 0.0, 1.0);
      emit(ta + f * (tb - ta), x, y, on, label);
      ref = level;
    }
  }

  // Releases, in time order, the events no later step can precede.
  void release(std::vector<LabelledEvent>& out, bool all) {
    const TimeUs horizon = all ? INT64_MAX : static_cast<TimeUs>(t_s * 1e6) - static_cast<TimeUs>(6 * cfg.jitter_us) - 2;
    auto by_time = [](const LabelledEvent& a, const LabelledEvent& b) {
      return std::tie(a.event.t, a.event.y, a.event.x) < std::tie(b.event.t, b.event.y, b.event.x);
    };
    std::sort(pending.begin(), pending.end(), by_time);
    auto cut = std::partition_point(pending.begin(), pending.end(), [&](const LabelledEvent& e) { return e.event.t < horizon; });
    out.insert(out.end(), pending.begin(), cut);
    pending.erase(pending.begin(), cut);
  }
};

SceneGenerator::SceneGenerator(const SceneConfig& config) : config_(config), impl_(std::make_unique<Impl>(config)) {}
SceneGenerator::~SceneGenerator() = default;

bool SceneGenerator::next(std::vector<LabelledEvent>& events, std::vector<TruthSample>& truth) {
  if (impl_->done) return false;
  const size_t before = events.size();
  while (events.size() == before && impl_->t_s < config_.duration_s) {
    for (int i = 0; i < 16 && impl_->t_s < config_.duration_s; ++i) impl_->advance(truth);
    impl_->release(events, false);
  }
  if (impl_->t_s >= config_.duration_s) {
    impl_->release(events, true);
    impl_->done = true;
  }
  return true;
}

int SceneGenerator::object_count() const { return static_cast<int>(impl_->objects.size()); }
std::string SceneGenerator::object_name(int i) const { return impl_->objects[static_cast<size_t>(i)].shape.name; }
double SceneGenerator::progress() const { return impl_->t_s / config_.duration_s; }

}  // namespace evms::gen
