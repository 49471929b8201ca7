#include "hrad/io/flush_faces.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "hrad/core/scene_checks.h"
#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

using P2 = Eigen::Vector2d;
using Poly2 = std::vector<P2>;

double signed_area(const Poly2& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const P2& u = p[i];
    const P2& v = p[(i + 1) % p.size()];
    a += u.x() * v.y() - u.y() * v.x();
  }
  return 0.5 * a;
}

// The part of the convex polygon `poly` to the left of the directed line a -> b (`left`) or to its
// right (Sutherland & Hodgman 1974, one clipping plane).
Poly2 clip(const Poly2& poly, const P2& a, const P2& b, bool left) {
  const P2 d = b - a;
  const auto side = [&](const P2& x) {
    const double s = d.x() * (x.y() - a.y()) - d.y() * (x.x() - a.x());
    return left ? s : -s;
  };
  Poly2 out;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const P2& p = poly[i];
    const P2& q = poly[(i + 1) % poly.size()];
    const double sp = side(p), sq = side(q);
    if (sp >= 0.0) out.push_back(p);
    if ((sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
  }
  return out;
}

// poly less the convex polygon `top` (counter-clockwise), as disjoint convex pieces: the k-th lies
// outside top's k-th edge and inside its edges before k.
std::vector<Poly2> subtract(const Poly2& poly, const Poly2& top) {
  std::vector<Poly2> pieces;
  Poly2 rest = poly;
  for (std::size_t k = 0; k < top.size() && rest.size() >= 3; ++k) {
    const P2& a = top[k];
    const P2& b = top[(k + 1) % top.size()];
    Poly2 outside = clip(rest, a, b, false);
    if (outside.size() >= 3) pieces.push_back(std::move(outside));
    rest = clip(rest, a, b, true);
  }
  return pieces;
}

// The convex hull of two convex polygons, counter-clockwise (Andrew 1979, monotone chain).
Poly2 hull_of(const Poly2& a, const Poly2& b) {
  Poly2 pts = a;
  pts.insert(pts.end(), b.begin(), b.end());
  std::sort(pts.begin(), pts.end(),
            [](const P2& u, const P2& v) { return u.x() < v.x() || (u.x() == v.x() && u.y() < v.y()); });
  const auto turn = [](const P2& o, const P2& u, const P2& v) {
    return (u.x() - o.x()) * (v.y() - o.y()) - (u.y() - o.y()) * (v.x() - o.x());
  };
  Poly2 h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], pts[i]) <= 0.0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(h[k - 2], h[k - 1], pts[i]) <= 0.0) --k;
    h[k++] = pts[i];
  }
  h.resize(k > 1 ? k - 1 : k);
  return h;
}

// Tops that tile a convex polygon between them (a picture's two triangles) are merged into it, so
// that the face beneath is cut by the polygon's edges only, into fewer and fatter pieces: two
// convex polygons that do not overlap tile their hull exactly when their areas add up to its.
std::vector<Poly2> merged(std::vector<Poly2> tops, double tol) {
  for (bool again = true; again;) {
    again = false;
    for (std::size_t i = 0; i < tops.size() && !again; ++i)
      for (std::size_t j = i + 1; j < tops.size() && !again; ++j) {
        Poly2 h = hull_of(tops[i], tops[j]);
        if (std::abs(signed_area(h) - signed_area(tops[i]) - signed_area(tops[j])) <= tol) {
          tops[i] = std::move(h);
          tops.erase(tops.begin() + static_cast<std::ptrdiff_t>(j));
          again = true;
        }
      }
  }
  return tops;
}

// Drops vertices that repeat or lie on the line through their neighbours (within `eps` of it), so
// that a piece's corners are corners.
Poly2 corners_of(Poly2 p, double eps) {
  bool changed = true;
  while (changed && p.size() >= 3) {
    changed = false;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const P2& prev = p[(i + p.size() - 1) % p.size()];
      const P2& next = p[(i + 1) % p.size()];
      const P2 d = next - prev;
      const double len = d.norm();
      const P2 e = p[i] - prev;
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

FlushCuts cut_flush_faces(Scene& scene) {
  FlushCuts cuts;
  const std::vector<std::pair<int, int>> pairs = flush_pairs(scene);
  if (pairs.empty()) return cuts;
  const auto [lo, hi] = scene.bounds();
  const double size = (hi - lo).norm();
  // Which lies on top (flush_faces.h): the smaller object, then the smaller face, then the later face.
  std::map<std::string, double> object_area;
  for (const Patch& p : scene.patches) object_area[p.group] += p.area;
  const auto on_top = [&](int fa, int fb) {
    const InputFace& a = scene.faces[static_cast<std::size_t>(fa)];
    const InputFace& b = scene.faces[static_cast<std::size_t>(fb)];
    const double ga = object_area[a.group], gb = object_area[b.group];
    if (ga != gb) return ga < gb;
    if (a.area != b.area) return a.area < b.area;
    return fa > fb;
  };
  std::vector<std::vector<int>> covers(scene.patches.size());  // per patch beneath: the patches on it
  for (const auto& [i, j] : pairs) {
    const int fi = scene.patches[static_cast<std::size_t>(i)].face,
              fj = scene.patches[static_cast<std::size_t>(j)].face;
    const auto [top, beneath] = on_top(fi, fj) ? std::pair{i, j} : std::pair{j, i};
    covers[static_cast<std::size_t>(beneath)].push_back(top);
    if (cuts.pairs++ == 0) {
      cuts.first_top = scene.patches[static_cast<std::size_t>(top)].face;
      cuts.first_beneath = scene.patches[static_cast<std::size_t>(beneath)].face;
    }
  }
  std::vector<Patch> patches;
  patches.reserve(scene.patches.size());
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    // Copied, not moved: a patch beneath may come after the patches on top of it.
    const Patch& b = scene.patches[i];
    if (covers[i].empty()) {
      patches.push_back(b);
      continue;
    }
    // In b's plane: origin at its first vertex, axes e1 and e2 = n x e1 (counter-clockwise seen from
    // the front stays counter-clockwise).
    const Vec3 o = b.vertices[0], n = b.normal;
    const Vec3 e1 = (b.vertices[1] - o).normalized(), e2 = n.cross(e1);
    const auto to2 = [&](const Vec3& x) { return P2((x - o).dot(e1), (x - o).dot(e2)); };
    Poly2 own;
    for (const Vec3& v : b.vertices) own.push_back(to2(v));
    std::vector<Poly2> tops;
    for (const int t : covers[i]) {
      Poly2 top;
      for (const Vec3& v : scene.patches[static_cast<std::size_t>(t)].vertices) top.push_back(to2(v));
      if (signed_area(top) < 0.0) std::reverse(top.begin(), top.end());
      tops.push_back(std::move(top));
    }
    std::vector<Poly2> rest = {own};
    for (const Poly2& top : merged(std::move(tops), 1e-9 * b.area)) {
      std::vector<Poly2> next;
      for (const Poly2& piece : rest)
        for (Poly2& cut : subtract(piece, top)) next.push_back(std::move(cut));
      rest = std::move(next);
    }
    // Pieces thinner than a millionth of the scene's size are dropped (an edge of the face on top
    // that lies along one of the face beneath, up to rounding).
    const double thin = 1e-6 * size;
    double kept = 0.0;
    for (const Poly2& piece : rest) {
      const Poly2 c = corners_of(piece, 1e-9 * size);
      if (c.size() < 3) continue;
      double diameter = 0.0;
      for (const P2& u : c)
        for (const P2& v : c) diameter = std::max(diameter, (u - v).norm());
      const double area = signed_area(c);
      if (!(area > thin * diameter)) continue;
      std::vector<Vec3> v3;
      for (const P2& u : c) v3.push_back(o + u.x() * e1 + u.y() * e2);
      auto add = [&](std::vector<Vec3> vertices) {
        Patch p = b;
        p.area = polygon_area(vertices);
        p.vertices = std::move(vertices);
        kept += p.area;
        patches.push_back(std::move(p));
      };
      if (v3.size() <= 4) {
        add(std::move(v3));
      } else {
        for (std::size_t k = 1; k + 1 < v3.size(); ++k) add({v3[0], v3[k], v3[k + 1]});
      }
    }
    cuts.covered_area += b.area - kept;
  }
  scene.patches = std::move(patches);
  std::vector<char> had(scene.faces.size(), 0);
  for (std::size_t f = 0; f < scene.faces.size(); ++f) {
    had[f] = !scene.faces[f].patches.empty();
    scene.faces[f].patches.clear();
    scene.faces[f].area = 0.0;
  }
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    InputFace& f = scene.faces[static_cast<std::size_t>(scene.patches[i].face)];
    f.patches.push_back(static_cast<int>(i));
    f.area += scene.patches[i].area;
  }
  for (std::size_t f = 0; f < scene.faces.size(); ++f)
    if (had[f] && scene.faces[f].patches.empty()) ++cuts.hidden_faces;
  return cuts;
}

}  // namespace hrad
