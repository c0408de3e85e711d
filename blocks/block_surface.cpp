#include "blocks/block_surface.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <unordered_map>

namespace rockmass::blocks {

namespace {

using geometry::Vec3;

/// A planar convex polygon in 3D, CCW about its outward normal.
using Polygon = std::vector<Vec3>;

/// A face of a piece, placed in its plane group.
struct PlanarFace {
  Polygon polygon;
  bool positive = true;  ///< outward normal along the group's normal (else opposite)
};

/// Faces of the block lying in one plane n.x = d.
struct PlaneGroup {
  Vec3 normal;  ///< unit
  double offset = 0.0;
  std::vector<PlanarFace> faces;
};

/// Twice the area vector of a polygon (Newell).
Vec3 areaVector(const Polygon& p) {
  Vec3 a = Vec3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) a += p[i].cross(p[(i + 1) % p.size()]);
  return a;
}

/// Whether a convex polygon is wider than `tol` somewhere: area > tol x perimeter / 2.
/// A thinner polygon is a round-off sliver: its vertices weld together.
bool thick(const Polygon& p, double tol) {
  if (p.size() < 3) return false;
  double perimeter = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) perimeter += (p[(i + 1) % p.size()] - p[i]).norm();
  return 0.5 * areaVector(p).norm() > 0.5 * tol * perimeter;
}

/// The part of convex `p` where side(x) = m.(x - q) <= 0 (with tolerance `tol` in length).
Polygon clipInside(const Polygon& p, const Vec3& m, const Vec3& q, double tol) {
  Polygon out;
  const std::size_t n = p.size();
  std::vector<double> s(n);
  for (std::size_t i = 0; i < n; ++i) {
    s[i] = m.dot(p[i] - q);
    if (std::abs(s[i]) <= tol) s[i] = 0.0;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if (s[i] <= 0.0) out.push_back(p[i]);
    if ((s[i] < 0.0 && s[j] > 0.0) || (s[i] > 0.0 && s[j] < 0.0)) {
      // From the lexicographically smaller end, so the point does not depend on direction.
      const bool forward =
          std::lexicographical_compare(p[i].data(), p[i].data() + 3, p[j].data(), p[j].data() + 3);
      const Vec3& a = forward ? p[i] : p[j];
      const Vec3& b = forward ? p[j] : p[i];
      const double sa = forward ? s[i] : s[j];
      const double sb = forward ? s[j] : s[i];
      out.push_back(a + (sa / (sa - sb)) * (b - a));
    }
  }
  return out;
}

/// p minus convex g (both in the plane with unit normal `normal`), as convex polygons wider
/// than `tol`. `g` is CCW about `normal` or about -normal (`g_ccw`).
std::vector<Polygon> difference(const Polygon& p, const Polygon& g, const Vec3& normal, bool g_ccw,
                                double tol) {
  // The edge planes of g, outward: m = edge x normal for a CCW polygon.
  std::vector<std::pair<Vec3, Vec3>> planes;
  for (std::size_t i = 0; i < g.size(); ++i) {
    const Vec3 e = g[(i + 1) % g.size()] - g[i];
    const double len = e.norm();
    if (len <= tol) continue;
    Vec3 m = e.cross(normal) / len;
    if (!g_ccw) m = -m;
    planes.emplace_back(m, g[i]);
  }
  // Overlap test first: most pairs of faces in a plane do not overlap.
  Polygon inside = p;
  for (const auto& [m, q] : planes) {
    inside = clipInside(inside, m, q, tol);
    if (inside.size() < 3) return {p};
  }
  if (!thick(inside, tol)) return {p};
  std::vector<Polygon> result;
  Polygon rest = p;
  for (const auto& [m, q] : planes) {
    Polygon outside = clipInside(rest, -m, q, tol);
    if (thick(outside, tol)) {
      result.push_back(std::move(outside));
    }
    rest = clipInside(rest, m, q, tol);
    if (rest.size() < 3) break;
  }
  return result;
}

/// Groups the faces of all pieces by plane: a face joins a group when its normal is
/// parallel to the group's (within 1e-6 in the cosine) and every vertex lies within `tol` of
/// the group's plane. Faces are taken from the largest down, so a group's plane comes from
/// its largest face. (The normal of a millimetre face is off by ~1e-10 and its offset n.x by
/// ~1e-9 m at 10 m from the origin, so taking its own plane split one plane into two groups,
/// and the faces between two pieces that were left in different groups stayed in the
/// surface as an internal sheet.)
std::vector<PlaneGroup> planeGroups(const Block& block, double tol) {
  struct Candidate {
    Polygon polygon;
    Vec3 normal;
    double area = 0.0;
  };
  std::vector<Candidate> candidates;
  for (const Piece& piece : block.pieces) {
    const geometry::Polyhedron& shape = piece.shape;
    for (std::size_t f = 0; f < shape.faces.size(); ++f) {
      Candidate c;
      for (int v : shape.faces[f]) c.polygon.push_back(shape.vertices[static_cast<std::size_t>(v)]);
      c.normal = geometry::faceNormal(shape, static_cast<int>(f));
      c.area = areaVector(c.polygon).norm();
      candidates.push_back(std::move(c));
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.area > b.area; });
  std::vector<PlaneGroup> groups;
  for (Candidate& c : candidates) {
    bool placed = false;
    for (PlaneGroup& g : groups) {
      const double cosine = c.normal.dot(g.normal);
      if (std::abs(cosine) < 1.0 - 1e-6) continue;
      const bool on_plane = std::all_of(c.polygon.begin(), c.polygon.end(), [&](const Vec3& p) {
        return std::abs(g.normal.dot(p) - g.offset) <= tol;
      });
      if (!on_plane) continue;
      g.faces.push_back({std::move(c.polygon), cosine > 0});
      placed = true;
      break;
    }
    if (placed) continue;
    double offset = 0.0;
    for (const Vec3& p : c.polygon) offset += c.normal.dot(p);
    offset /= static_cast<double>(c.polygon.size());
    groups.push_back({c.normal, offset, {{std::move(c.polygon), true}}});
  }
  return groups;
}

/// Vertices welded within a tolerance through a hash grid.
class Welder {
 public:
  explicit Welder(double tol) : tol_(tol), cell_(4.0 * tol) {}

  int add(const Vec3& p) {
    const auto key = cellOf(p);
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = grid_.find(hash({key[0] + dx, key[1] + dy, key[2] + dz}));
          if (it == grid_.end()) continue;
          for (int v : it->second) {
            if ((vertices_[static_cast<std::size_t>(v)] - p).norm() <= tol_) return v;
          }
        }
      }
    }
    const int index = static_cast<int>(vertices_.size());
    vertices_.push_back(p);
    grid_[hash(key)].push_back(index);
    return index;
  }
  const std::vector<Vec3>& vertices() const { return vertices_; }
  std::vector<Vec3>& vertices() { return vertices_; }

 private:
  std::array<std::int64_t, 3> cellOf(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / cell_)),
            static_cast<std::int64_t>(std::floor(p.y() / cell_)),
            static_cast<std::int64_t>(std::floor(p.z() / cell_))};
  }
  static std::uint64_t hash(const std::array<std::int64_t, 3>& k) {
    return static_cast<std::uint64_t>(k[0]) * 73856093ULL ^
           static_cast<std::uint64_t>(k[1]) * 19349663ULL ^
           static_cast<std::uint64_t>(k[2]) * 83492791ULL;
  }

  double tol_;
  double cell_;
  std::vector<Vec3> vertices_;
  std::unordered_map<std::uint64_t, std::vector<int>> grid_;
};

/// Inserts into every polygon edge the welded vertices lying on it (no T-junctions).
void insertEdgeVertices(std::vector<std::vector<int>>& loops, const std::vector<Vec3>& vertices,
                        double tol) {
  std::vector<int> by_x(vertices.size());
  for (std::size_t i = 0; i < by_x.size(); ++i) by_x[i] = static_cast<int>(i);
  std::sort(by_x.begin(), by_x.end(), [&](int a, int b) {
    return std::make_tuple(vertices[static_cast<std::size_t>(a)].x(), a) <
           std::make_tuple(vertices[static_cast<std::size_t>(b)].x(), b);
  });
  std::vector<double> xs(by_x.size());
  for (std::size_t i = 0; i < by_x.size(); ++i)
    xs[i] = vertices[static_cast<std::size_t>(by_x[i])].x();
  for (std::vector<int>& loop : loops) {
    std::vector<int> refined;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int ia = loop[i];
      const int ib = loop[(i + 1) % loop.size()];
      const Vec3& a = vertices[static_cast<std::size_t>(ia)];
      const Vec3& b = vertices[static_cast<std::size_t>(ib)];
      refined.push_back(ia);
      const Vec3 e = b - a;
      const double len2 = e.squaredNorm();
      const auto lo = std::lower_bound(xs.begin(), xs.end(), std::min(a.x(), b.x()) - tol);
      const auto hi = std::upper_bound(xs.begin(), xs.end(), std::max(a.x(), b.x()) + tol);
      std::vector<std::pair<double, int>> on_edge;
      for (auto it = lo; it != hi; ++it) {
        const int c = by_x[static_cast<std::size_t>(it - xs.begin())];
        if (c == ia || c == ib) continue;
        const Vec3& p = vertices[static_cast<std::size_t>(c)];
        const double t = (p - a).dot(e) / len2;
        if (t <= 0.0 || t >= 1.0) continue;
        if ((a + t * e - p).norm() > tol) continue;
        on_edge.emplace_back(t, c);
      }
      std::sort(on_edge.begin(), on_edge.end());
      for (const auto& [t, c] : on_edge) refined.push_back(c);
    }
    loop = std::move(refined);
  }
}

/// An edge of more than two triangles and the pairs of triangles of its wedges.
struct MultipleEdge {
  int a = 0, b = 0;  ///< its vertices before the copies
  std::vector<std::array<int, 2>> pairs;
};

/// Union-find over triangle indices.
struct Components {
  std::vector<int> parent;
  int find(int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  }
  void join(int a, int b) { parent[static_cast<std::size_t>(find(a))] = find(b); }
};

}  // namespace

void splitNonManifold(TriangleSurface& surface) {
  const std::size_t n = surface.triangles.size();
  // The triangles around each undirected edge.
  std::map<std::pair<int, int>, std::vector<int>> edges;
  for (std::size_t t = 0; t < n; ++t) {
    const auto& tri = surface.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int a = tri[static_cast<std::size_t>(k)],
                b = tri[static_cast<std::size_t>((k + 1) % 3)];
      edges[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(t));
    }
  }
  // Which triangles are joined across each edge: the two of a manifold edge; around an edge
  // of four or more (two sheets of the block touching along it), each triangle with the one
  // that closes the same solid wedge. Seen along a -> b, a triangle that runs a -> b has its
  // outward normal towards increasing angle (the solid just below its angle), one that runs
  // b -> a the other way: in angle order, each b -> a triangle is joined to the next one.
  std::vector<std::array<int, 2>> joins;
  std::vector<MultipleEdge> multiple;
  for (const auto& [edge, around] : edges) {
    if (around.size() == 2) {
      joins.push_back({around[0], around[1]});
      continue;
    }
    const Vec3& a = surface.vertices[static_cast<std::size_t>(edge.first)];
    const Vec3 e = (surface.vertices[static_cast<std::size_t>(edge.second)] - a).normalized();
    const Vec3 u = e.unitOrthogonal();
    const Vec3 w = e.cross(u);
    std::vector<std::pair<double, int>> sorted;  // (angle, triangle)
    for (const int t : around) {
      const auto& tri = surface.triangles[static_cast<std::size_t>(t)];
      int third = tri[0];
      for (const int v : tri) {
        if (v != edge.first && v != edge.second) third = v;
      }
      const Vec3 c = surface.vertices[static_cast<std::size_t>(third)] - a;
      sorted.emplace_back(std::atan2(c.dot(w), c.dot(u)), t);
    }
    std::sort(sorted.begin(), sorted.end());
    const auto runs_forward = [&](int t) {  // the triangle runs edge.first -> edge.second
      const auto& tri = surface.triangles[static_cast<std::size_t>(t)];
      for (int k = 0; k < 3; ++k) {
        if (tri[static_cast<std::size_t>(k)] == edge.first &&
            tri[static_cast<std::size_t>((k + 1) % 3)] == edge.second) {
          return true;
        }
      }
      return false;
    };
    // Two faces at the same angle, one each way, are the two sides of a crack that closes
    // on the edge (no solid between them: the one that runs a -> b first) or of a sliver of
    // solid (the other way): the order that makes the wedges alternate around the edge.
    const auto pairs_of = [&](bool crack_first) {
      std::vector<std::pair<double, int>> order = sorted;
      for (std::size_t i = 0; i + 1 < order.size(); ++i) {
        if (order[i + 1].first - order[i].first <= 1e-9 &&
            runs_forward(order[i].second) != runs_forward(order[i + 1].second) &&
            runs_forward(order[i + 1].second) == crack_first) {
          std::swap(order[i], order[i + 1]);
        }
      }
      std::vector<std::array<int, 2>> found;
      for (std::size_t i = 0; i < order.size(); ++i) {
        const int t = order[i].second;
        const int next = order[(i + 1) % order.size()].second;
        if (!runs_forward(t) && runs_forward(next)) found.push_back({t, next});
      }
      return found;
    };
    std::vector<std::array<int, 2>> pairs = pairs_of(true);
    if (pairs.size() * 2 != around.size()) pairs = pairs_of(false);
    if (pairs.size() * 2 != around.size()) {
      // Not wedges that alternate around the edge (faces that coincide, or do not turn
      // the same way): left as they are, all joined, rather than cut into a hole.
      for (std::size_t i = 1; i < around.size(); ++i) joins.push_back({around[0], around[i]});
      continue;
    }
    joins.insert(joins.end(), pairs.begin(), pairs.end());
    multiple.push_back({edge.first, edge.second, pairs});
  }
  // Around each vertex, the triangles joined across the edges at that vertex make one
  // sheet; every sheet after the first gets its own copy of the vertex.
  std::vector<std::vector<int>> at_vertex(surface.vertices.size());
  for (std::size_t t = 0; t < n; ++t) {
    for (const int v : surface.triangles[t])
      at_vertex[static_cast<std::size_t>(v)].push_back(static_cast<int>(t));
  }
  Components components{std::vector<int>(n)};
  std::vector<std::vector<std::array<int, 2>>> joins_at(surface.vertices.size());
  for (const auto& [t, s] : joins) {
    const auto& a = surface.triangles[static_cast<std::size_t>(t)];
    const auto& b = surface.triangles[static_cast<std::size_t>(s)];
    for (const int v : a) {
      if (std::find(b.begin(), b.end(), v) != b.end())
        joins_at[static_cast<std::size_t>(v)].push_back({t, s});
    }
  }
  const std::size_t original = surface.vertices.size();
  for (std::size_t v = 0; v < original; ++v) {
    const std::vector<int>& fan = at_vertex[v];
    if (fan.size() < 2) continue;
    for (const int t : fan) components.parent[static_cast<std::size_t>(t)] = t;
    for (const auto& [t, s] : joins_at[v]) components.join(t, s);
    std::map<int, int> copy;   // sheet root -> vertex index
    for (const int t : fan) {  // in triangle order: deterministic
      const int root = components.find(t);
      auto [it, added] = copy.try_emplace(root, -1);
      if (added) {
        if (copy.size() == 1) {
          it->second = static_cast<int>(v);
        } else {
          it->second = static_cast<int>(surface.vertices.size());
          surface.vertices.push_back(surface.vertices[v]);
        }
      }
      for (int& corner : surface.triangles[static_cast<std::size_t>(t)]) {
        if (corner == static_cast<int>(v)) corner = it->second;
      }
    }
  }
  // An edge whose wedges are joined elsewhere around both its ends (a block that touches
  // itself along an edge and is connected around it) keeps one vertex pair after the copies:
  // each wedge after the first then gets the edge's midpoint as a vertex of its own, its two
  // triangles split in two there, so that the wedges share no edge.
  // A triangle on two such edges is split for the first and must be found for the second:
  // `children` keeps the triangles each one was split into, and an edge is found again by
  // its ends' coordinates (copies keep them).
  std::vector<std::vector<int>> children(surface.triangles.size());
  // The triangle (t or one split from it) that has an edge from `pa` to `pb`, with the
  // indices of those two vertices; {-1, -1, -1} when none has.
  const auto locate = [&](int t, const Vec3& pa, const Vec3& pb) {
    std::vector<int> todo{t};
    while (!todo.empty()) {
      const int u = todo.back();
      todo.pop_back();
      int ia = -1, ib = -1;
      for (const int v : surface.triangles[static_cast<std::size_t>(u)]) {
        if (surface.vertices[static_cast<std::size_t>(v)] == pa) ia = v;
        if (surface.vertices[static_cast<std::size_t>(v)] == pb) ib = v;
      }
      if (ia >= 0 && ib >= 0) return std::array<int, 3>{u, ia, ib};
      // Every triangle has its entry: `children` grows with the triangles.
      todo.insert(todo.end(), children[static_cast<std::size_t>(u)].begin(),
                  children[static_cast<std::size_t>(u)].end());
    }
    return std::array<int, 3>{-1, -1, -1};
  };
  for (const MultipleEdge& multi : multiple) {
    const Vec3 pa = surface.vertices[static_cast<std::size_t>(multi.a)];
    const Vec3 pb = surface.vertices[static_cast<std::size_t>(multi.b)];
    const std::array<int, 3> first = locate(multi.pairs[0][0], pa, pb);
    if (first[0] < 0) continue;
    for (std::size_t p = 1; p < multi.pairs.size(); ++p) {
      const std::array<int, 3> here = locate(multi.pairs[p][0], pa, pb);
      if (here[0] < 0 || here[1] != first[1] || here[2] != first[2]) continue;  // apart
      const int middle = static_cast<int>(surface.vertices.size());
      surface.vertices.push_back(0.5 * (pa + pb));
      for (const int t : multi.pairs[p]) {
        const std::array<int, 3> holder = locate(t, pa, pb);
        if (holder[0] < 0) continue;
        // (x, y, z) with x -> y the edge: (x, m, z) and (m, y, z), the same orientation.
        auto& tri = surface.triangles[static_cast<std::size_t>(holder[0])];
        for (int k = 0; k < 3; ++k) {
          const int x = tri[static_cast<std::size_t>(k)];
          const int y = tri[static_cast<std::size_t>((k + 1) % 3)];
          const int z = tri[static_cast<std::size_t>((k + 2) % 3)];
          if ((x == holder[1] && y == holder[2]) || (x == holder[2] && y == holder[1])) {
            tri = {x, middle, z};
            children[static_cast<std::size_t>(holder[0])].push_back(
                static_cast<int>(surface.triangles.size()));
            surface.triangles.push_back({middle, y, z});
            children.emplace_back();
            break;
          }
        }
      }
    }
  }
}

TriangleSurface blockSurface(const Block& block) {
  const double diagonal = block.bounds.diagonal();
  const double tol = 1e-10 * diagonal;

  // 1. Real face parts: in each plane, every face minus the opposite faces of the block.
  std::vector<Polygon> kept;
  for (const PlaneGroup& group : planeGroups(block, tol)) {
    for (std::size_t i = 0; i < group.faces.size(); ++i) {
      std::vector<Polygon> parts = {group.faces[i].polygon};
      for (std::size_t j = 0; j < group.faces.size() && !parts.empty(); ++j) {
        if (group.faces[j].positive == group.faces[i].positive) continue;
        std::vector<Polygon> next;
        for (const Polygon& part : parts) {
          for (Polygon& q : difference(part, group.faces[j].polygon, group.normal,
                                       group.faces[j].positive, tol)) {
            next.push_back(std::move(q));
          }
        }
        parts = std::move(next);
      }
      for (Polygon& part : parts) kept.push_back(std::move(part));
    }
  }

  // 2. Weld, drop repeated points, insert vertices lying on edges.
  Welder welder(tol);
  std::vector<std::vector<int>> loops;
  std::vector<std::size_t> corners;  // corners of each loop before edge insertion
  for (const Polygon& polygon : kept) {
    std::vector<int> loop;
    for (const Vec3& p : polygon) {
      const int v = welder.add(p);
      if (loop.empty() || loop.back() != v) loop.push_back(v);
    }
    while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
    if (loop.size() < 3) continue;
    corners.push_back(loop.size());
    loops.push_back(std::move(loop));
  }
  insertEdgeVertices(loops, welder.vertices(), tol);

  // 3. Triangulate: a fan from the first corner, or from the centroid when points were
  //    inserted on edges or the corner fan has a flat triangle (a polygon with collinear
  //    corners: the full Xiangjiaba model had 2 zero-area triangles).
  TriangleSurface surface;
  surface.vertices = welder.vertices();
  const double flat_area = 1e-12 * diagonal * diagonal;
  const auto corner_fan_is_flat = [&](const std::vector<int>& loop) {
    const Vec3& apex = surface.vertices[static_cast<std::size_t>(loop[0])];
    for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
      const Vec3 a = surface.vertices[static_cast<std::size_t>(loop[k])] - apex;
      const Vec3 b = surface.vertices[static_cast<std::size_t>(loop[k + 1])] - apex;
      if (0.5 * a.cross(b).norm() <= flat_area) return true;
    }
    return false;
  };
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const std::vector<int>& loop = loops[l];
    if (loop.size() == corners[l] && !corner_fan_is_flat(loop)) {
      for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
        surface.triangles.push_back({loop[0], loop[k], loop[k + 1]});
      }
      continue;
    }
    Vec3 c = Vec3::Zero();
    for (int v : loop) c += surface.vertices[static_cast<std::size_t>(v)];
    c /= static_cast<double>(loop.size());
    const int ci = static_cast<int>(surface.vertices.size());
    surface.vertices.push_back(c);
    for (std::size_t k = 0; k < loop.size(); ++k) {
      surface.triangles.push_back({ci, loop[k], loop[(k + 1) % loop.size()]});
    }
  }
  splitNonManifold(surface);
  return surface;
}

geometry::Polyhedron toPolyhedron(const TriangleSurface& surface) {
  geometry::Polyhedron p;
  p.vertices = surface.vertices;
  for (const auto& t : surface.triangles) p.faces.push_back({t[0], t[1], t[2]});
  return p;
}

}  // namespace rockmass::blocks
