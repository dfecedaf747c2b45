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
  // Not std::hypot: glibc's guards against overflow make it half the generator's time, and
  // these are pixel-scale lengths.
  double norm() const { return std::sqrt(x * x + y * y); }
};

// A rotation by an angle, its cosine and sine computed once.
struct Rotation {
  explicit Rotation(double a) : c(std::cos(a)), s(std::sin(a)) {}
  Vec operator()(Vec v) const { return {c * v.x - s * v.y, s * v.x + c * v.y}; }
  double c, s;
};

Vec rotate(Vec v, double a) { return Rotation(a)(v); }

// A shape in its own frame, centred on its geometric centre. Signed distance is negative
// inside. Polygons (convex or not) are exact; the ellipse is the usual first-order
// approximation, which only shapes the one-pixel anti-aliasing ramp.
struct Shape {
  enum class Kind { kCircle, kEllipse, kRing, kPolygon } kind;
  std::string name;
  double a = 0, b = 0;            // radius, ellipse half-axes, or ring radius and half-width
  std::vector<Vec> vertices;      // polygon, counter-clockwise
  double bound = 0;               // radius of a circle that holds the shape

  double sdf(Vec p) const {
    switch (kind) {
      case Kind::kCircle: return p.norm() - a;
      case Kind::kEllipse: {
        const double k = Vec{p.x / a, p.y / b}.norm();
        return (k - 1.0) * std::min(a, b);
      }
      case Kind::kRing: return std::abs(p.norm() - a) - b;
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

  void scale(double s) {
    for (Vec& v : vertices) v = v * s;
    a *= s;
    b *= s;
    bound *= s;
  }
};

Shape circle(double r) { return {Shape::Kind::kCircle, "circle", r, r, {}, r}; }
Shape ellipse(double a, double b) { return {Shape::Kind::kEllipse, "ellipse", a, b, {}, std::max(a, b)}; }
Shape ring(double r, double half_width) { return {Shape::Kind::kRing, "ring", r, half_width, {}, r + half_width}; }
Shape polygon(std::string name, std::vector<Vec> v) {
  // Centre on the outline's centroid (the edges' midpoints weighted by their lengths): the
  // centre of mass of the events a uniformly firing outline gives, and the truth centre.
  Vec centroid;
  double perimeter = 0;
  for (size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    const double length = (v[i] - v[j]).norm();
    centroid = centroid + (v[i] + v[j]) * (0.5 * length);
    perimeter += length;
  }
  centroid = centroid * (1.0 / perimeter);
  double bound = 0;
  for (Vec& p : v) p = p - centroid, bound = std::max(bound, p.norm());
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
// Concave shapes, each about 2r across.
Shape ell(double r) {
  const double t = 0.4 * r;
  return polygon("L", {{-r, -r}, {r, -r}, {r, -r + t}, {-r + t, -r + t}, {-r + t, r}, {-r, r}});
}
Shape cross(double r) {
  const double t = 0.3 * r;
  return polygon("cross", {{-t, -r}, {t, -r}, {t, -t}, {r, -t}, {r, t}, {t, t}, {t, r}, {-t, r}, {-t, t}, {-r, t}, {-r, -t}, {-t, -t}});
}
Shape chevron(double r) {
  const double t = 0.45 * r;
  return polygon("chevron", {{-r, -r}, {-r + t, -r}, {r, 0}, {-r + t, r}, {-r, r}, {r - t, 0}});
}

// A shape of the scattered layout with diameter d: the nine poster shapes, a thin bar, and
// the concave L, cross, ring and chevron.
Shape any_shape(int kind, double d, Random& rng) {
  const double r = d / 2;
  switch (kind) {
    case 0: return circle(r);
    case 1: return ellipse(r, r * rng.uniform(0.4, 0.7));
    case 2: return regular("triangle", 3, r);
    case 3: return box("square", r * 0.75, r * 0.75);
    case 4: return box("rectangle", r, r * 0.5);
    case 5: return regular("pentagon", 5, r);
    case 6: return regular("hexagon", 6, r);
    case 7: return star(r, r * 0.42);
    case 8: return regular("diamond", 4, r, 0);
    case 9: return box("bar", r, std::max(1.0, rng.uniform(1.0, 1.6)));
    case 10: return ell(r * 0.75);
    case 11: return cross(r * 0.75);
    case 12: return ring(r * 0.8, std::max(1.0, r * rng.uniform(0.1, 0.2)));
    default: return chevron(r * 0.75);
  }
}
constexpr int kShapeKinds = 14;

struct Object {
  Shape shape;
  Vec home;           // poster position of the centre
  double angle;       // orientation on the poster
  double intensity;   // reflectance on a white (1.0) poster
  bool mover = false; // moves on its own
  Vec amplitude{};    // a mover's displacement amplitude, per axis
  double hz_x = 0, hz_y = 0;
  double phase_x = 0, phase_y = 0;
};

}  // namespace

bool parse_motion(const std::string& name, Motion& out) {
  if (name == "still") out = Motion::kStill;
  else if (name == "translation") out = Motion::kTranslation;
  else if (name == "rotation") out = Motion::kRotation;
  else if (name == "zoom") out = Motion::kZoom;
  else if (name == "6dof") out = Motion::kSixDof;
  else if (name == "shake") out = Motion::kShake;
  else return false;
  return true;
}

const char* motion_name(Motion m) {
  switch (m) {
    case Motion::kStill: return "still";
    case Motion::kTranslation: return "translation";
    case Motion::kRotation: return "rotation";
    case Motion::kZoom: return "zoom";
    case Motion::kSixDof: return "6dof";
    case Motion::kShake: return "shake";
  }
  return "?";
}

struct SceneGenerator::Impl {
  SceneConfig cfg;
  Random rng;
  std::vector<Object> objects;
  Vec centre;           // sensor centre, px
  double motion_phase[8];

  // Per-pixel sensor state.
  std::vector<double> log_ref, log_prev, th_on, th_off;
  std::vector<TimeUs> last_fire;
  std::vector<std::int8_t> owner;
  std::vector<std::uint32_t> visited;
  std::uint32_t step = 0;

  struct HotPixel {
    int x, y;
    double next_s;
  };
  std::vector<HotPixel> hot;

  double t_s = 0;                  // simulated time reached, s
  double next_noise_s = 0;
  TimeUs next_truth_us = 0;
  std::vector<LabelledEvent> pending;  // generated, not yet released (jitter reordering)
  bool done = false;

  explicit Impl(const SceneConfig& c) : cfg(c), rng(c.seed) {
    centre = {(cfg.width - 1) / 2.0, (cfg.height - 1) / 2.0};
    if (cfg.layout == Layout::kPoster) build_poster();
    else build_scattered();
    add_movers();
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
    const Instant first(*this, 0.0);
    for (int y = 0; y < cfg.height; ++y) {
      for (int x = 0; x < cfg.width; ++x) {
        int who = -1;
        const double l = std::log(intensity(x, y, first, who));
        const size_t i = index(x, y);
        log_ref[i] = log_prev[i] = l;
        owner[i] = static_cast<std::int8_t>(who);
      }
    }
    next_noise_s = cfg.noise_hz > 0 ? rng.exponential(cfg.noise_hz * n) : 1e300;
    for (int k = 0; k < cfg.hot_pixels; ++k) {
      hot.push_back({static_cast<int>(rng.below(static_cast<std::uint64_t>(cfg.width))),
                     static_cast<int>(rng.below(static_cast<std::uint64_t>(cfg.height))), rng.exponential(cfg.hot_pixel_hz)});
    }
  }

  size_t index(int x, int y) const { return static_cast<size_t>(y) * cfg.width + x; }
  double size_scale() const { return std::min(cfg.width / 240.0, cfg.height / 180.0); }

  // Nine shapes on a jittered 3x3 grid that spans more than the field of view, with random
  // size, orientation and contrast.
  void build_poster() {
    const double sx = cfg.width / 240.0, sy = cfg.height / 180.0;
    const double s = size_scale();
    std::vector<Shape> shapes = {
        circle(15 * s),           ellipse(19 * s, 11 * s),     regular("triangle", 3, 19 * s),
        box("square", 13 * s, 13 * s), box("rectangle", 20 * s, 10 * s), regular("pentagon", 5, 16 * s),
        regular("hexagon", 6, 16 * s), star(19 * s, 8 * s),      regular("diamond", 4, 17 * s, 0),
    };
    // Shuffle which shape sits where.
    for (size_t i = shapes.size() - 1; i > 0; --i) std::swap(shapes[i], shapes[rng.below(i + 1)]);
    for (int gy = 0; gy < 3; ++gy) {
      for (int gx = 0; gx < 3; ++gx) {
        Object o{shapes[static_cast<size_t>(gy * 3 + gx)], {}, 0, 0};
        o.shape.scale(rng.uniform(0.85, 1.15));
        o.home = {cfg.width * (0.5 + (gx - 1) * 0.36) + rng.uniform(-7, 7) * sx,
                  cfg.height * (0.5 + (gy - 1) * 0.36) + rng.uniform(-6, 6) * sy};
        o.angle = rng.uniform(0, 2 * M_PI);
        o.intensity = rng.uniform(0.04, 0.35);
        objects.push_back(std::move(o));
      }
    }
  }

  // `objects` shapes of any kind and size, apart from each other, on a poster that reaches
  // beyond the field of view when the camera moves (so that shapes leave and enter it).
  void build_scattered() {
    const double margin = cfg.motion == Motion::kStill ? -0.05 : 0.15;
    const Vec lo{-margin * cfg.width, -margin * cfg.height}, hi{(1 + margin) * cfg.width, (1 + margin) * cfg.height};
    for (int k = 0; k < cfg.objects; ++k) {
      const double d = cfg.size_min_px * std::pow(cfg.size_max_px / cfg.size_min_px, rng.uniform());
      Object o{any_shape(static_cast<int>(rng.below(kShapeKinds)), d, rng), {}, rng.uniform(0, 2 * M_PI), 0};
      o.intensity = rng.uniform() < cfg.low_contrast_share ? rng.uniform(0.55, 0.75) : rng.uniform(0.04, 0.35);
      // Apart from the shapes placed so far, by a gap of 3 px or more; shrink when crowded.
      for (int attempt = 0;; ++attempt) {
        const double r = o.shape.bound;
        o.home = {rng.uniform(lo.x + r, hi.x - r), rng.uniform(lo.y + r, hi.y - r)};
        bool clear = true;
        for (const Object& p : objects) clear = clear && (o.home - p.home).norm() > r + p.shape.bound + 3;
        if (clear) break;
        if (attempt % 40 == 39) o.shape.scale(0.85);
      }
      objects.push_back(std::move(o));
    }
  }

  // Movers: the last `movers` shapes move on their own and are drawn in front. Crossing ones
  // slide to and fro across another shape's place; the others wander on Lissajous paths.
  void add_movers() {
    const int movers = std::min<int>(cfg.movers, static_cast<int>(objects.size()));
    const double w = cfg.width, h = cfg.height;
    for (int m = 0; m < movers; ++m) {
      Object& o = objects[objects.size() - 1 - static_cast<size_t>(m)];
      o.mover = true;
      if (cfg.crossing && objects.size() > 1) {
        const size_t others = objects.size() - static_cast<size_t>(movers);
        const Object& target = objects[others > 0 ? rng.below(others) : 0];
        // Through the target, from one side of it to the other.
        const double a = rng.uniform(0, 2 * M_PI);
        const double reach = target.shape.bound + o.shape.bound + rng.uniform(0.1, 0.25) * std::min(w, h);
        o.home = target.home;
        o.amplitude = {reach * std::cos(a), reach * std::sin(a)};
        // Over the target once or twice in the scene, the first time near its middle: a period
        // of 0.6 to 1.2 scene lengths (in motion time, t * speed), in phase at mid-scene.
        const double u_length = cfg.duration_s * cfg.speed;
        const double hz = 1.0 / (u_length * rng.uniform(0.6, 1.2));
        o.hz_x = o.hz_y = hz;
        o.phase_x = o.phase_y = -2 * M_PI * hz * u_length / 2 + rng.uniform(-0.5, 0.5);
      } else {
        o.amplitude = {rng.uniform(0.1, 0.3) * w, rng.uniform(0.1, 0.3) * h};
        o.home = {std::clamp(o.home.x, o.amplitude.x + o.shape.bound, w - o.amplitude.x - o.shape.bound),
                  std::clamp(o.home.y, o.amplitude.y + o.shape.bound, h - o.amplitude.y - o.shape.bound)};
        o.hz_x = cfg.mover_speed_px_s * rng.uniform(0.5, 1.5) / (4 * o.amplitude.x);
        o.hz_y = cfg.mover_speed_px_s * rng.uniform(0.5, 1.5) / (4 * o.amplitude.y);
        o.phase_x = rng.uniform(0, 2 * M_PI);
        o.phase_y = rng.uniform(0, 2 * M_PI);
      }
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
    auto wave = [&](double amplitude, double hz, int k) { return amplitude * std::sin(2 * M_PI * hz * u + ph[k]); };
    Pose p;
    switch (cfg.motion) {
      case Motion::kStill: break;
      case Motion::kTranslation:
        p.d = {wave(45 * w, 0.45, 0), wave(32 * w, 0.31, 1)};
        break;
      case Motion::kRotation:
        p.theta = wave(0.75, 0.30, 2);
        p.d = {wave(6 * w, 0.2, 0), wave(5 * w, 0.17, 1)};
        break;
      case Motion::kZoom:
        p.zoom = std::exp(wave(0.35, 0.25, 3));
        p.d = {wave(5 * w, 0.2, 0), wave(4 * w, 0.17, 1)};
        break;
      case Motion::kSixDof:
        p.d = {wave(30 * w, 0.37, 0), wave(22 * w, 0.29, 1)};
        p.theta = wave(0.35, 0.23, 2);
        p.zoom = std::exp(wave(0.22, 0.21, 3));
        break;
      case Motion::kShake:
        // A hand holding the camera: a few small, faster tremors on top of a slow drift.
        p.d = {wave(4 * w, 1.7, 0) + wave(2.5 * w, 3.1, 4) + wave(1.5 * w, 5.3, 5) + wave(8 * w, 0.3, 6),
               wave(3 * w, 2.3, 1) + wave(2 * w, 3.7, 7) + wave(6 * w, 0.23, 2)};
        p.theta = wave(0.03, 1.3, 3);
        break;
    }
    return p;
  }
  Vec to_poster(Vec pix, const Pose& p) const { return rotate(pix - centre, p.theta) * p.zoom + centre + p.d; }
  Vec to_pixel(Vec poster, const Pose& p) const { return rotate(poster - centre - p.d, -p.theta) * (1.0 / p.zoom) + centre; }

  Vec object_centre(const Object& o, double t) const {
    if (!o.mover) return o.home;
    const double u = t * cfg.speed;
    return o.home + Vec{o.amplitude.x * std::sin(2 * M_PI * o.hz_x * u + o.phase_x), o.amplitude.y * std::sin(2 * M_PI * o.hz_y * u + o.phase_y)};
  }

  // What intensity() needs at one instant, computed once for every pixel it is asked about:
  // the pose's rotation, each object's centre and its rotation into the object's frame.
  struct Instant {
    Instant(const Impl& scene, double t) : pose(scene.pose(t)), camera(pose.theta) {
      for (const Object& o : scene.objects) centres.push_back(scene.object_centre(o, t)), unrotate.emplace_back(-o.angle);
    }
    Pose pose;
    Rotation camera;
    std::vector<Vec> centres;
    std::vector<Rotation> unrotate;
  };

  // Intensity seen by pixel (x, y) at an instant, and the topmost object covering it.
  double intensity(int x, int y, const Instant& at, int& who) const {
    const Pose& p = at.pose;
    const Vec q = at.camera(Vec{double(x), double(y)} - centre) * p.zoom + centre + p.d;  // to_poster
    double value = 1.0;
    who = -1;
    for (size_t k = 0; k < objects.size(); ++k) {
      const Object& o = objects[k];
      const Vec rel = q - at.centres[k];
      if (rel.norm() > o.shape.bound + 2 * p.zoom) continue;
      const double d = o.shape.sdf(at.unrotate[k](rel)) / p.zoom;  // in pixels
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
    const Instant at_t1(*this, t1);
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
          const double l1 = std::log(intensity(x, y, at_t1, who));
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
    for (HotPixel& hp : hot) {
      for (; hp.next_s <= t1; hp.next_s += rng.exponential(cfg.hot_pixel_hz)) emit(hp.next_s, hp.x, hp.y, rng.uniform() < 0.5, kNoiseLabel);
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
