#include "geometry/loop_subdivision.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <cmath>
#include <string>

namespace lantern {

namespace {

constexpr int32_t kNone = -1;

inline uint32_t next(uint32_t k) { return k == 2 ? 0 : k + 1; }
inline uint32_t prev(uint32_t k) { return k == 0 ? 2 : k - 1; }

// A triangle mesh with the adjacency Loop's rules need. Corner c = 3 f + k
// is vertex k of face f; its edge runs from that vertex to the next one.
struct Topology {
  std::vector<glm::uvec3> tri;
  std::vector<int32_t> across;       // per corner: the face on the other side of its edge, or kNone
  std::vector<uint32_t> edge;        // per corner: the index of its (undirected) edge
  std::vector<int32_t> some_corner;  // per vertex: one corner at that vertex
  uint32_t edges = 0;
};

std::string face_name(size_t f) { return "triangle " + std::to_string(f); }

Topology connect(std::vector<glm::uvec3> tri, uint32_t vertex_count) {
  Topology t;
  const size_t corners = tri.size() * 3;
  struct Half {
    uint64_t key;  // (smaller vertex, larger vertex)
    uint32_t corner;
  };
  std::vector<Half> halves(corners);
  t.some_corner.assign(vertex_count, kNone);
  for (size_t f = 0; f < tri.size(); ++f)
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t a = tri[f][k], b = tri[f][next(k)];
      if (a == b) throw std::invalid_argument(face_name(f) + " uses vertex " + std::to_string(a) + " twice");
      halves[3 * f + k] = {uint64_t(std::min(a, b)) << 32 | std::max(a, b), uint32_t(3 * f + k)};
      t.some_corner[a] = int32_t(3 * f + k);
    }
  tbb::parallel_sort(halves.begin(), halves.end(), [](const Half& x, const Half& y) {
    return x.key < y.key || (x.key == y.key && x.corner < y.corner);
  });
  t.across.assign(corners, kNone);
  t.edge.resize(corners);
  for (size_t i = 0; i < corners;) {
    size_t j = i + 1;
    while (j < corners && halves[j].key == halves[i].key) ++j;
    const std::string ends = std::to_string(halves[i].key >> 32) + "-" + std::to_string(halves[i].key & 0xffffffffu);
    if (j - i > 2)
      throw std::invalid_argument("edge " + ends + " is shared by " + std::to_string(j - i) +
                                  " triangles; at most two may share an edge");
    if (j - i == 2) {
      const uint32_t c0 = halves[i].corner, c1 = halves[i + 1].corner;
      if (tri[c0 / 3][c0 % 3] == tri[c1 / 3][c1 % 3])
        throw std::invalid_argument(face_name(c0 / 3) + " and " + face_name(c1 / 3) + " run along edge " + ends +
                                    " the same way; neighbouring triangles must be wound alike");
      t.across[c0] = int32_t(c1 / 3);
      t.across[c1] = int32_t(c0 / 3);
    }
    for (size_t h = i; h < j; ++h) t.edge[halves[h].corner] = t.edges;
    ++t.edges;
    i = j;
  }
  t.tri = std::move(tri);
  return t;
}

// Which corner of face f is vertex v.
inline uint32_t corner_of(const Topology& t, uint32_t f, uint32_t v) {
  const glm::uvec3& q = t.tri[f];
  return 3 * f + (q[0] == v ? 0u : q[1] == v ? 1u : 2u);
}

// Vertex v's one-ring, in pbrt-v4's order: around an interior vertex, each
// face reads (v, ring[j + 1], ring[j]); around a boundary vertex each face
// reads (v, ring[j], ring[j + 1]), from one boundary neighbour to the other.
// Returns whether v is on the boundary. `incident`: how many corners v has,
// to catch fans that meet only at v.
bool one_ring(const Topology& t, uint32_t v, uint32_t incident, std::vector<uint32_t>& ring) {
  ring.clear();
  const uint32_t start = uint32_t(t.some_corner[v]);
  uint32_t c = start, faces = 0;
  bool boundary = false;
  // Forward (across each corner's own edge) until back at the start or off the boundary.
  for (;;) {
    const int32_t g = t.across[c];
    if (g == kNone) {
      boundary = true;
      break;
    }
    const uint32_t gc = corner_of(t, uint32_t(g), v);
    if (gc == start) break;
    c = gc;
    if (++faces > incident) break;  // cannot happen on a consistent mesh; never loop forever
  }
  faces = 0;
  if (!boundary) {
    c = start;
    do {
      ring.push_back(t.tri[c / 3][next(c % 3)]);
      c = corner_of(t, uint32_t(t.across[c]), v);
      ++faces;
    } while (c != start && faces <= incident);
  } else {
    ring.push_back(t.tri[c / 3][next(c % 3)]);
    for (;;) {
      ring.push_back(t.tri[c / 3][prev(c % 3)]);
      ++faces;
      const int32_t g = t.across[3 * (c / 3) + prev(c % 3)];
      if (g == kNone || faces > incident) break;
      c = corner_of(t, uint32_t(g), v);
    }
  }
  if (faces != incident)
    throw std::invalid_argument("vertex " + std::to_string(v) +
                                " joins separate fans of triangles; a subdivision "
                                "surface must be a manifold there");
  return boundary;
}

float beta(size_t valence) { return valence == 3 ? 3.f / 16.f : 3.f / (8.f * float(valence)); }

Vec3 ring_sum(const std::vector<Vec3>& P, const std::vector<uint32_t>& ring) {
  Vec3 s(0.f);
  for (uint32_t r : ring) s += P[r];
  return s;
}

// The even (old) vertices' new positions.
std::vector<Vec3> even_vertices(const Topology& t, const std::vector<Vec3>& P, const std::vector<uint32_t>& incident) {
  std::vector<Vec3> out(P.size());
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(P.size())), [&](const tbb::blocked_range<uint32_t>& r) {
    std::vector<uint32_t> ring;
    for (uint32_t v = r.begin(); v != r.end(); ++v) {
      if (one_ring(t, v, incident[v], ring)) {
        out[v] = 0.75f * P[v] + 0.125f * (P[ring.front()] + P[ring.back()]);
      } else {
        const float b = beta(ring.size());
        out[v] = (1.f - float(ring.size()) * b) * P[v] + b * ring_sum(P, ring);
      }
    }
  });
  return out;
}

uint32_t other_vertex(const glm::uvec3& q, uint32_t a, uint32_t b) {
  return q[0] != a && q[0] != b ? q[0] : q[1] != a && q[1] != b ? q[1] : q[2];
}

// One level: every face splits into four (pbrt's children order), every
// edge gets a new (odd) vertex numbered after the old ones.
std::vector<Vec3> refine(Topology& t, const std::vector<Vec3>& P, const std::vector<uint32_t>& incident,
                         std::vector<glm::uvec3>& faces) {
  std::vector<Vec3> Q = even_vertices(t, P, incident);
  const uint32_t nv = uint32_t(P.size());
  Q.resize(size_t(nv) + t.edges);
  for (uint32_t c = 0; c < t.tri.size() * 3; ++c) {
    const glm::uvec3& q = t.tri[c / 3];
    const uint32_t a = q[c % 3], b = q[next(c % 3)];
    if (t.across[c] == kNone) {
      Q[nv + t.edge[c]] = 0.5f * (P[a] + P[b]);
    } else if (t.across[c] > int32_t(c / 3)) {  // each shared edge once
      const uint32_t d = other_vertex(t.tri[size_t(t.across[c])], a, b);
      Q[nv + t.edge[c]] = 0.375f * (P[a] + P[b]) + 0.125f * (P[q[prev(c % 3)]] + P[d]);
    }
  }
  faces.clear();
  faces.reserve(t.tri.size() * 4);
  for (uint32_t f = 0; f < t.tri.size(); ++f) {
    const glm::uvec3& q = t.tri[f];
    const uint32_t e0 = nv + t.edge[3 * f], e1 = nv + t.edge[3 * f + 1], e2 = nv + t.edge[3 * f + 2];
    faces.emplace_back(q[0], e0, e2);
    faces.emplace_back(e0, q[1], e1);
    faces.emplace_back(e2, e1, q[2]);
    faces.emplace_back(e0, e1, e2);
  }
  return Q;
}

std::vector<uint32_t> count_incident(const std::vector<glm::uvec3>& tri, size_t vertex_count) {
  std::vector<uint32_t> n(vertex_count, 0);
  for (const glm::uvec3& q : tri)
    for (int k = 0; k < 3; ++k) ++n[q[k]];
  return n;
}

// The limit surface's tangents at v (Hoppe et al. 1994), from limit positions.
Vec3 limit_normal(const std::vector<Vec3>& L, uint32_t v, bool boundary, const std::vector<uint32_t>& ring) {
  const size_t n = ring.size();
  Vec3 S(0.f), T(0.f);
  if (!boundary) {
    for (size_t j = 0; j < n; ++j) {
      const float phi = 2.f * kPi * float(j) / float(n);
      S += std::cos(phi) * L[ring[j]];
      T += std::sin(phi) * L[ring[j]];
    }
  } else {
    S = L[ring[n - 1]] - L[ring[0]];
    if (n == 2) {
      T = L[ring[0]] + L[ring[1]] - 2.f * L[v];
    } else if (n == 3) {
      T = L[ring[1]] - L[v];
    } else if (n == 4) {
      T = -L[ring[0]] + 2.f * L[ring[1]] + 2.f * L[ring[2]] - L[ring[3]] - 2.f * L[v];
    } else {
      const float theta = kPi / float(n - 1);
      T = std::sin(theta) * (L[ring[0]] + L[ring[n - 1]]);
      for (size_t k = 1; k + 1 < n; ++k) T += (2.f * std::cos(theta) - 2.f) * std::sin(float(k) * theta) * L[ring[k]];
      T = -T;
    }
  }
  return glm::cross(S, T);
}

}  // namespace

SubdividedMesh loop_subdivide(const std::vector<Vec3>& P, const std::vector<int>& indices, int levels) {
  if (levels < 0) throw std::invalid_argument("\"levels\" is " + std::to_string(levels) + "; expected 0 or more");
  if (indices.size() % 3 != 0)
    throw std::invalid_argument("\"indices\" has " + std::to_string(indices.size()) +
                                " values, expected a multiple of 3");
  const uint64_t base = indices.size() / 3;
  if (levels > 13 || (base << (2 * levels)) > kMaxSubdividedTriangles)
    throw std::invalid_argument(std::to_string(levels) + " levels would refine " + std::to_string(base) +
                                " triangles beyond " + std::to_string(kMaxSubdividedTriangles) + "; use fewer levels");
  // Only the vertices the triangles use, in their order in P.
  std::vector<int64_t> remap(P.size(), -1);
  std::vector<Vec3> V;
  std::vector<glm::uvec3> tri(base);
  for (size_t i = 0; i < indices.size(); ++i) {
    const int x = indices[i];
    if (x < 0 || size_t(x) >= P.size())
      throw std::invalid_argument("index " + std::to_string(x) + " is out of range: there are " +
                                  std::to_string(P.size()) + " vertices");
    if (remap[size_t(x)] < 0) {
      remap[size_t(x)] = int64_t(V.size());
      V.push_back(P[size_t(x)]);
    }
  }
  for (size_t i = 0; i < indices.size(); ++i) tri[i / 3][int(i % 3)] = uint32_t(remap[size_t(indices[i])]);

  Topology t = connect(std::move(tri), uint32_t(V.size()));
  std::vector<uint32_t> incident = count_incident(t.tri, V.size());
  std::vector<glm::uvec3> faces;
  for (int level = 0; level < levels; ++level) {
    V = refine(t, V, incident, faces);
    t = connect(std::move(faces), uint32_t(V.size()));
    incident = count_incident(t.tri, V.size());
  }

  // Push to the limit surface, then take the tangents there.
  SubdividedMesh out;
  std::vector<uint8_t> on_boundary(V.size());
  out.positions.resize(V.size());
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(V.size())), [&](const tbb::blocked_range<uint32_t>& r) {
    std::vector<uint32_t> ring;
    for (uint32_t v = r.begin(); v != r.end(); ++v) {
      on_boundary[v] = one_ring(t, v, incident[v], ring);
      if (on_boundary[v]) {
        out.positions[v] = 0.6f * V[v] + 0.2f * (V[ring.front()] + V[ring.back()]);
      } else {
        const float n = float(ring.size()), gamma = 1.f / (n + 3.f / (8.f * beta(ring.size())));
        out.positions[v] = (1.f - n * gamma) * V[v] + gamma * ring_sum(V, ring);
      }
    }
  });
  out.normals.resize(V.size());
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(V.size())), [&](const tbb::blocked_range<uint32_t>& r) {
    std::vector<uint32_t> ring;
    for (uint32_t v = r.begin(); v != r.end(); ++v) {
      one_ring(t, v, incident[v], ring);
      out.normals[v] = limit_normal(out.positions, v, on_boundary[v], ring);
    }
  });
  // A degenerate ring (all neighbours in a line) has no tangent plane: the
  // faces' own normals stand in, oriented as the limit normals are.
  std::vector<uint8_t> flat(V.size(), 0);
  for (size_t v = 0; v < V.size(); ++v)
    if (!(glm::dot(out.normals[v], out.normals[v]) > 0.f) || !is_finite(out.normals[v])) {
      flat[v] = 1;
      out.normals[v] = Vec3(0.f);
    }
  for (const glm::uvec3& q : t.tri) {
    const Vec3 n = glm::cross(out.positions[q[2]] - out.positions[q[0]], out.positions[q[1]] - out.positions[q[0]]);
    for (int k = 0; k < 3; ++k)
      if (flat[q[k]]) out.normals[q[k]] += n;
  }
  out.triangles = std::move(t.tri);
  return out;
}

}  // namespace lantern
