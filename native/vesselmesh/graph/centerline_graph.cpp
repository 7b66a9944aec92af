#include "vesselmesh/graph/centerline_graph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <utility>

#include "vesselmesh/error.hpp"
#include "vesselmesh/graph/union_find.hpp"

namespace vesselmesh {

namespace {

/// Radius of each input point: its own, or for per-edge radii the smallest of its edges (0 when on
/// no edge, so that it only merges with exact duplicates).
std::vector<double> point_radius(const CenterlineData& data) {
  if (!data.radius.empty()) return data.radius;
  std::vector<double> r(data.points.size(), std::numeric_limits<double>::infinity());
  for (std::size_t e = 0; e < data.edges.size(); ++e)
    for (int32_t v : data.edges[e]) r[v] = std::min(r[v], data.edge_radius[e]);
  for (double& x : r)
    if (std::isinf(x)) x = 0.0;
  return r;
}

/// Representative of every point after merging coincident ones. Points are hashed into cells twice
/// as large as the largest tolerance, so a point's partners lie in the 2×2×2 cells on its side.
std::vector<int32_t> merge_coincident(const std::vector<Vec3>& points, const std::vector<double>& r) {
  const std::size_t n = points.size();
  UnionFind sets(n);
  std::vector<int32_t> rep(n);
  const double cell = 2.0 * kCoincidentFraction * *std::max_element(r.begin(), r.end());
  if (!(cell > 0.0)) {  // only when every point is on no edge
    std::iota(rep.begin(), rep.end(), 0);
    return rep;
  }
  using Key = std::array<int64_t, 3>;
  auto hash = [](const Key& k) {
    // Unsigned: cells of a data set lying far from the origin, in radii, overflow a signed product.
    uint64_t h = uint64_t(k[0]);
    h = h * 0x9e3779b97f4a7c15ULL ^ uint64_t(k[1]);
    h = h * 0x9e3779b97f4a7c15ULL ^ uint64_t(k[2]);
    h ^= h >> 33, h *= 0xff51afd7ed558ccdULL, h ^= h >> 33;  // mixed, for a table of 2^k slots
    return h;
  };
  // Element by element: std::array's == calls memcmp, half the graph's time at a million points.
  auto same = [](const Key& a, const Key& b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; };
  // Clamped to where int64 holds them: cells so far out only share keys, and partners are checked by
  // distance anyway.
  auto cell_of = [](double x) { return static_cast<int64_t>(std::clamp(std::floor(x), -4e18, 4e18)); };
  auto key_of = [&](const Vec3& q) { return Key{cell_of(q.x()), cell_of(q.y()), cell_of(q.z())}; };
  std::vector<Vec3> scaled(n);
  std::vector<std::pair<Key, int32_t>> sorted(n);
  for (std::size_t i = 0; i < n; ++i) {
    scaled[i] = points[i] / cell;
    sorted[i] = {key_of(scaled[i]), static_cast<int32_t>(i)};
  }
  std::sort(sorted.begin(), sorted.end());
  // Cell -> its first entry in `sorted`, in an open-addressing table (a std::unordered_map took most of
  // the graph's second at a million points).
  std::size_t size = 16;
  while (size < 2 * n) size *= 2;
  std::vector<int64_t> table(size, -1);
  auto slot_of = [&](const Key& k) {
    std::size_t slot = hash(k) & (size - 1);
    while (table[slot] >= 0 && !same(sorted[table[slot]].first, k)) slot = (slot + 1) & (size - 1);
    return slot;
  };
  for (std::size_t s = 0; s < n; ++s)
    if (s == 0 || !same(sorted[s].first, sorted[s - 1].first)) table[slot_of(sorted[s].first)] = static_cast<int64_t>(s);
  for (std::size_t i = 0; i < n; ++i) {
    Key base, step;
    int crossed = 0;  // the axes along which a partner may lie in the next cell: bit a for axis a
    for (int a = 0; a < 3; ++a) {
      base[a] = cell_of(scaled[i][a]);
      const double f = scaled[i][a] - std::floor(scaled[i][a]);
      step[a] = f < 0.5 ? -1 : 1;
      // Twice the tolerance, against rounding: a point further than that from both sides of its cell has
      // its partners in the same cell along this axis (most points, where radii vary).
      if (std::min(f, 1 - f) * cell <= 2 * kCoincidentFraction * r[i]) crossed |= 1 << a;
    }
    for (int corner = 0; corner < 8; ++corner) {
      if ((corner & crossed) != corner) continue;
      const Key k{base[0] + (corner & 1 ? step[0] : 0), base[1] + (corner & 2 ? step[1] : 0),
                  base[2] + (corner & 4 ? step[2] : 0)};
      const int64_t found = table[slot_of(k)];
      if (found < 0) continue;
      for (std::size_t s = static_cast<std::size_t>(found); s < n && same(sorted[s].first, k); ++s) {
        const int32_t j = sorted[s].second;
        if (static_cast<std::size_t>(j) <= i) continue;
        const double tol = kCoincidentFraction * std::min(r[i], r[j]);
        if ((points[i] - points[j]).norm() <= tol) sets.unite(static_cast<int32_t>(i), j);
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) rep[i] = sets.find(static_cast<int32_t>(i));
  return rep;
}

void build_adjacency(CenterlineGraph& g) {
  const std::size_t n = g.points.size();
  g.offsets.assign(n + 1, 0);
  for (const Edge& e : g.edges) ++g.offsets[e[0] + 1], ++g.offsets[e[1] + 1];
  for (std::size_t v = 0; v < n; ++v) g.offsets[v + 1] += g.offsets[v];
  g.incident.resize(g.offsets[n]);
  std::vector<int32_t> fill(g.offsets.begin(), g.offsets.end() - 1);
  for (std::size_t e = 0; e < g.edges.size(); ++e)
    for (int32_t v : g.edges[e]) g.incident[fill[v]++] = static_cast<int32_t>(e);
}

void find_components(CenterlineGraph& g) {
  UnionFind sets(g.points.size());
  for (const Edge& e : g.edges) sets.unite(e[0], e[1]);
  g.component.assign(g.points.size(), -1);
  std::vector<int32_t> id_of_rep(g.points.size(), -1);
  g.components = 0;
  for (std::size_t v = 0; v < g.points.size(); ++v) {
    int32_t rep = sets.find(static_cast<int32_t>(v));
    if (id_of_rep[rep] < 0) id_of_rep[rep] = g.components++;
    g.component[v] = id_of_rep[rep];
  }
}

/// One root per component: the first root the file names in it, else its widest terminal (ties:
/// lowest index), else (a ring) its widest point.
void choose_roots(CenterlineGraph& g, const std::vector<int32_t>& file_roots) {
  std::vector<int32_t> root(g.components, -1);
  for (int32_t r : file_roots)
    if (root[g.component[r]] < 0) root[g.component[r]] = r;
  auto better = [&](int32_t candidate, int32_t current) {
    return current < 0 || g.radius[candidate] > g.radius[current];
  };
  std::vector<int32_t> widest_terminal(g.components, -1), widest(g.components, -1);
  for (int32_t v = 0; v < static_cast<int32_t>(g.points.size()); ++v) {
    const int32_t c = g.component[v];
    if (g.degree(v) == 1 && better(v, widest_terminal[c])) widest_terminal[c] = v;
    if (better(v, widest[c])) widest[c] = v;
  }
  g.roots.resize(g.components);
  for (int32_t c = 0; c < g.components; ++c)
    g.roots[c] = root[c] >= 0 ? root[c] : widest_terminal[c] >= 0 ? widest_terminal[c] : widest[c];
}

void find_branches(CenterlineGraph& g) {
  std::vector<char> used(g.edges.size(), 0);
  auto walk = [&](int32_t start, int32_t first_edge) {
    Branch b;
    b.points.push_back(start);
    int32_t v = start, e = first_edge;
    while (true) {
      used[e] = 1;
      b.edges.push_back(e);
      v = g.other(e, v);
      b.points.push_back(v);
      if (g.degree(v) != 2 || v == start) break;
      const int32_t a = g.incident[g.offsets[v]], c = g.incident[g.offsets[v] + 1];
      e = a == e ? c : a;
      if (used[e]) break;
    }
    g.branches.push_back(std::move(b));
  };
  for (int32_t v = 0; v < static_cast<int32_t>(g.points.size()); ++v)
    if (g.degree(v) != 2)
      for (int32_t k = g.offsets[v]; k < g.offsets[v + 1]; ++k)
        if (!used[g.incident[k]]) walk(v, g.incident[k]);
  // What is left are rings of degree-2 points.
  for (int32_t e = 0; e < static_cast<int32_t>(g.edges.size()); ++e)
    if (!used[e]) walk(g.edges[e][0], e);
}

}  // namespace

CenterlineGraph build_graph(const CenterlineData& data, const std::string& source) {
  CenterlineGraph g;
  NormalisationReport& report = g.report;
  report.input_points = static_cast<int64_t>(data.points.size());
  report.input_edges = static_cast<int64_t>(data.edges.size());
  g.radius_per_edge = data.radius.empty();

  const std::vector<double> r = point_radius(data);
  // A coordinate within a millionth of the smallest radius of zero is zero: a denormal or a number near
  // one (1e-320) would underflow the products of the exact geometric predicates (geometry/predicates.hpp)
  // and spoil the hulls of the joints. Before the merging, so that it sees where the points are; relative
  // to the smallest radius, so that a huge radius does not move its point's coordinates far.
  double smallest = std::numeric_limits<double>::infinity();
  for (double x : r)
    if (x > 0) smallest = std::min(smallest, x);
  std::vector<Vec3> points = data.points;
  for (Vec3& p : points)
    for (int k = 0; k < 3; ++k)
      if (p[k] != 0 && std::abs(p[k]) <= kCoincidentFraction * smallest) p[k] = 0, ++report.snapped_coordinates;
  const std::vector<int32_t> rep = merge_coincident(points, r);
  for (std::size_t i = 0; i < rep.size(); ++i) report.merged_points += rep[i] != static_cast<int32_t>(i);

  // Drop self-loops and merge parallel edges into the first, which keeps the larger radius at each end
  // (a vessel traced twice is as wide as the wider trace); new point ids follow first use by an edge.
  std::vector<int32_t> new_id(data.points.size(), -1);
  auto id_of = [&](int32_t original) {
    int32_t& id = new_id[rep[original]];
    if (id < 0) {
      id = static_cast<int32_t>(g.points.size());
      g.points.push_back(points[rep[original]]);
    }
    return id;
  };
  std::unordered_map<uint64_t, std::size_t> kept;  // (lower, higher representative) -> edge in g.edges
  kept.reserve(data.edges.size() * 2);
  for (std::size_t e = 0; e < data.edges.size(); ++e) {
    const auto [a, b] = data.edges[e];
    if (rep[a] == rep[b]) {
      ++report.zero_length_edges;
      continue;
    }
    const std::array<double, 2> ends = g.radius_per_edge
                                           ? std::array<double, 2>{data.edge_radius[e], data.edge_radius[e]}
                                           : std::array<double, 2>{data.radius[a], data.radius[b]};
    const uint64_t lo = std::min(rep[a], rep[b]), hi = std::max(rep[a], rep[b]);
    const auto [it, first] = kept.emplace(lo << 32 | hi, g.edges.size());
    if (!first) {
      ++report.duplicate_edges;
      std::array<double, 2>& r_kept = g.end_radius[it->second];
      const bool same_way = g.edges[it->second][0] == new_id[rep[a]];
      r_kept[0] = std::max(r_kept[0], ends[same_way ? 0 : 1]);
      r_kept[1] = std::max(r_kept[1], ends[same_way ? 1 : 0]);
      continue;
    }
    g.edges.push_back({id_of(a), id_of(b)});
    g.end_radius.push_back(ends);
  }
  for (std::size_t i = 0; i < rep.size(); ++i)
    report.isolated_points += rep[i] == static_cast<int32_t>(i) && new_id[i] < 0;
  if (g.edges.empty())
    throw InputError(source, "",
                     "every edge joins points that merge (each within a millionth of a radius of the next): "
                     "nothing to mesh");

  g.radius.assign(g.points.size(), 0.0);
  for (std::size_t e = 0; e < g.edges.size(); ++e)
    for (int k = 0; k < 2; ++k) g.radius[g.edges[e][k]] = std::max(g.radius[g.edges[e][k]], g.end_radius[e][k]);

  std::vector<int32_t> file_roots;
  for (int32_t root : data.roots)
    if (new_id[rep[root]] >= 0) file_roots.push_back(new_id[rep[root]]);

  build_adjacency(g);
  find_components(g);
  choose_roots(g, file_roots);
  find_branches(g);
  g.loops = static_cast<int64_t>(g.edges.size()) - static_cast<int64_t>(g.points.size()) + g.components;
  return g;
}

int64_t CenterlineGraph::joints() const {
  int64_t n = 0;
  for (std::size_t v = 0; v + 1 < offsets.size(); ++v) n += degree(static_cast<int32_t>(v)) >= 3;
  return n;
}

int64_t CenterlineGraph::terminals() const {
  int64_t n = 0;
  for (std::size_t v = 0; v + 1 < offsets.size(); ++v) n += degree(static_cast<int32_t>(v)) == 1;
  return n;
}

int32_t CenterlineGraph::max_degree() const {
  int32_t d = 0;
  for (std::size_t v = 0; v + 1 < offsets.size(); ++v) d = std::max(d, degree(static_cast<int32_t>(v)));
  return d;
}

CenterlineData centerline_data(const CenterlineGraph& g, const std::vector<char>& keep) {
  CenterlineData d;
  d.edges.reserve(g.edges.size());
  auto kept = [&](std::size_t e) { return keep.empty() || keep[e]; };
  // Per graph point, its copies: (radius, index in d). Per edge radii: one copy, in the graph's order;
  // per point: one per radius the ends of its edges have, mostly one, a joint's few at most.
  std::vector<std::vector<std::pair<double, int32_t>>> copies(g.points.size());
  auto add = [&](int32_t v, double r) {
    d.points.push_back(g.points[v]);
    copies[v].emplace_back(r, static_cast<int32_t>(d.points.size()) - 1);
    return copies[v].back().second;
  };
  if (g.radius_per_edge) {
    std::vector<char> used(g.points.size(), 0);
    for (std::size_t e = 0; e < g.edges.size(); ++e)
      if (kept(e)) used[g.edges[e][0]] = used[g.edges[e][1]] = 1;
    for (std::size_t v = 0; v < g.points.size(); ++v)
      if (used[v]) add(static_cast<int32_t>(v), 0);
    for (std::size_t e = 0; e < g.edges.size(); ++e)
      if (kept(e)) {
        d.edges.push_back({copies[g.edges[e][0]][0].second, copies[g.edges[e][1]][0].second});
        d.edge_radius.push_back(g.end_radius[e][0]);
      }
  } else {
    auto copy_of = [&](int32_t v, double r) {
      for (const auto& [radius, index] : copies[v])
        if (radius == r) return index;
      d.radius.push_back(r);
      return add(v, r);
    };
    for (std::size_t e = 0; e < g.edges.size(); ++e)
      if (kept(e))
        d.edges.push_back({copy_of(g.edges[e][0], g.end_radius[e][0]), copy_of(g.edges[e][1], g.end_radius[e][1])});
  }
  for (int32_t root : g.roots)
    if (!copies[root].empty()) d.roots.push_back(copies[root].front().second);
  return d;
}

namespace {

/// Where the polyline between two points a radius apart is this many times as long as the straight way
/// and holds kDenseEdges edges or more (points a quarter radius apart or closer), it is jittered
/// (vessel_arc). A smooth curve that long over its chord turns by 140° within a radius, a hairpin tighter
/// than its tube; jitter of a tenth of the radius on points a twentieth of it apart makes the polyline three
/// times as long (vmtk-aorta-centerline, the median over its spans). Where points lie nearly a radius apart
/// the way is the vessel's: a hairpin of three points at brava-records BH0022's root, a vessel of radius 1.5
/// turning back within 3, lost the tube round its bend counted straight.
constexpr double kJitteredWay = 1.25;
constexpr std::size_t kDenseEdges = 4;

}  // namespace

std::vector<double> vessel_arc(const CenterlineGraph& g, const Branch& b) {
  const std::size_t k = b.points.size() - 1;
  auto at = [&](std::size_t i) -> const Vec3& { return g.points[b.points[i]]; };
  std::vector<double> own(k + 1, 0.0), arc(k + 1, 0.0);
  for (std::size_t i = 1; i <= k; ++i) own[i] = own[i - 1] + (at(i) - at(i - 1)).norm();
  for (std::size_t counted = 0, i = 1; i <= k; ++i) {
    const double apart = (at(i) - at(counted)).norm();
    const double radius = std::min(g.radius[b.points[counted]], g.radius[b.points[i]]);
    if (apart < radius && i < k) continue;
    // The last piece may end within a radius of where it starts (a ring comes back to its start): it counts
    // no more than a radius of its way there.
    const double way = own[i] - own[counted];
    const double straight = std::min(way, std::max(apart, radius));
    const bool dense = i - counted >= kDenseEdges;
    const double kept = dense && way > kJitteredWay * straight ? straight / way : 1.0;
    for (std::size_t j = counted + 1; j <= i; ++j) arc[j] = arc[counted] + kept * (own[j] - own[counted]);
    counted = i;
  }
  return arc;
}

std::vector<double> vessel_lengths(const CenterlineGraph& g) {
  std::vector<double> length(g.edges.size(), 0.0);
  for (const Branch& b : g.branches) {
    const std::vector<double> arc = vessel_arc(g, b);
    for (std::size_t i = 0; i < b.edges.size(); ++i) length[b.edges[i]] = arc[i + 1] - arc[i];
  }
  return length;
}

}  // namespace vesselmesh
