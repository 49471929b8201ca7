#include "hrad/geometry/convex_clip.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

// The convex hull of two convex polygons, counter-clockwise (Andrew 1979, monotone chain).
Polygon2 hull_of(const Polygon2& a, const Polygon2& b) {
  Polygon2 pts = a;
  pts.insert(pts.end(), b.begin(), b.end());
  if (pts.size() < 3) return pts;
  std::sort(pts.begin(), pts.end(),
            [](const Point2& u, const Point2& v) { return u.x() < v.x() || (u.x() == v.x() && u.y() < v.y()); });
  const auto turn = [](const Point2& o, const Point2& u, const Point2& v) {
    return (u.x() - o.x()) * (v.y() - o.y()) - (u.y() - o.y()) * (v.x() - o.x());
  };
  Polygon2 h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], pts[i]) <= 0.0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(h[k - 2], h[k - 1], pts[i]) <= 0.0) --k;
    h[k++] = pts[i];
  }
  h.resize(k - 1);
  return h;
}

// Drops corners that repeat or lie on the line through their neighbours (within `eps` of it).
Polygon2 corners_of(Polygon2 p, double eps) {
  for (bool changed = true; changed && p.size() >= 3;) {
    changed = false;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Point2& prev = p[(i + p.size() - 1) % p.size()];
      const Point2& next = p[(i + 1) % p.size()];
      const Point2 d = next - prev, e = p[i] - prev;
      const double len = d.norm();
      const double off = len > 0.0 ? std::abs(d.x() * e.y() - d.y() * e.x()) / len : e.norm();
      if (off <= eps) {
        p.erase(p.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        break;
      }
    }
  }
  return p;
}

}  // namespace

double signed_area(const Polygon2& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Point2& u = p[i];
    const Point2& v = p[(i + 1) % p.size()];
    a += u.x() * v.y() - u.y() * v.x();
  }
  return 0.5 * a;
}

Polygon2 clip(const Polygon2& poly, const Point2& a, const Point2& b, bool left) {
  const Point2 d = b - a;
  const auto side = [&](const Point2& x) {
    const double s = d.x() * (x.y() - a.y()) - d.y() * (x.x() - a.x());
    return left ? s : -s;
  };
  Polygon2 out;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point2& p = poly[i];
    const Point2& q = poly[(i + 1) % poly.size()];
    const double sp = side(p), sq = side(q);
    if (sp >= 0.0) out.push_back(p);
    if ((sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
  }
  return out;
}

std::vector<Polygon2> subtract(const Polygon2& poly, const Polygon2& cutter) {
  std::vector<Polygon2> pieces;
  Polygon2 rest = poly;
  for (std::size_t k = 0; k < cutter.size() && rest.size() >= 3; ++k) {
    const Point2& a = cutter[k];
    const Point2& b = cutter[(k + 1) % cutter.size()];
    Polygon2 outside = clip(rest, a, b, false);
    if (outside.size() >= 3) pieces.push_back(std::move(outside));
    rest = clip(rest, a, b, true);
  }
  return pieces;
}

Polygon2 intersect(const Polygon2& poly, const Polygon2& cutter) {
  Polygon2 rest = poly;
  for (std::size_t k = 0; k < cutter.size() && rest.size() >= 3; ++k)
    rest = clip(rest, cutter[k], cutter[(k + 1) % cutter.size()], true);
  return rest;
}

std::vector<Polygon2> merged(std::vector<Polygon2> cutters, double tol) {
  for (bool again = true; again;) {
    again = false;
    for (std::size_t i = 0; i < cutters.size() && !again; ++i)
      for (std::size_t j = i + 1; j < cutters.size() && !again; ++j) {
        Polygon2 h = hull_of(cutters[i], cutters[j]);
        if (std::abs(signed_area(h) - signed_area(cutters[i]) - signed_area(cutters[j])) <= tol) {
          cutters[i] = std::move(h);
          cutters.erase(cutters.begin() + static_cast<std::ptrdiff_t>(j));
          again = true;
        }
      }
  }
  return cutters;
}

PatchFrame::PatchFrame(const Patch& p)
    : origin(p.vertices[0]), e1((p.vertices[1] - p.vertices[0]).normalized()), e2(p.normal.cross(e1)) {}

Polygon2 PatchFrame::counter_clockwise(const std::vector<Vec3>& vertices) const {
  Polygon2 poly;
  for (const Vec3& v : vertices) poly.push_back(to2(v));
  if (signed_area(poly) < 0.0) std::reverse(poly.begin(), poly.end());
  return poly;
}

double append_pieces(const Patch& p, const PatchFrame& frame, const std::vector<Polygon2>& pieces, double size,
                     std::vector<Patch>* out) {
  double appended = 0.0;
  for (const Polygon2& piece : pieces) {
    const Polygon2 c = corners_of(piece, 1e-9 * size);
    if (c.size() < 3) continue;
    double diameter = 0.0;
    for (const Point2& u : c)
      for (const Point2& v : c) diameter = std::max(diameter, (u - v).norm());
    if (!(signed_area(c) > 1e-6 * size * diameter)) continue;
    std::vector<Vec3> v3;
    for (const Point2& u : c) v3.push_back(frame.to3(u));
    const auto add = [&](std::vector<Vec3> vertices) {
      Patch q = p;
      q.area = polygon_area(vertices);
      q.vertices = std::move(vertices);
      appended += q.area;
      out->push_back(std::move(q));
    };
    if (v3.size() <= 4) {
      add(std::move(v3));
    } else {
      for (std::size_t k = 1; k + 1 < v3.size(); ++k) add({v3[0], v3[k], v3[k + 1]});
    }
  }
  return appended;
}

double append_cut(const Patch& p, const std::vector<const Patch*>& cutters, bool keep_inside, double size,
                  std::vector<Patch>* out) {
  const PatchFrame frame(p);
  std::vector<Polygon2> outlines;
  for (const Patch* c : cutters) outlines.push_back(frame.counter_clockwise(c->vertices));
  std::vector<Polygon2> pieces = {frame.counter_clockwise(p.vertices)};
  for (const Polygon2& outline : merged(std::move(outlines), 1e-9 * p.area)) {
    std::vector<Polygon2> next;
    for (const Polygon2& piece : pieces) {
      for (Polygon2& outside : subtract(piece, outline)) next.push_back(std::move(outside));
      if (!keep_inside) continue;
      Polygon2 inside = intersect(piece, outline);
      if (inside.size() >= 3) next.push_back(std::move(inside));
    }
    pieces = std::move(next);
  }
  return append_pieces(p, frame, pieces, size, out);
}

std::vector<Patch> cut_patches(const std::vector<Patch>& patches, const std::vector<std::vector<int>>& cutters,
                               bool keep_inside, double size, double* removed) {
  std::vector<Patch> out;
  out.reserve(patches.size());
  double dropped = 0.0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    if (cutters[i].empty()) {
      out.push_back(patches[i]);
      continue;
    }
    std::vector<const Patch*> outlines;
    for (const int c : cutters[i]) outlines.push_back(&patches[static_cast<std::size_t>(c)]);
    dropped += patches[i].area - append_cut(patches[i], outlines, keep_inside, size, &out);
  }
  if (removed != nullptr) *removed = dropped;
  return out;
}

}  // namespace hrad
