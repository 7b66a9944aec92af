#include "vesselmesh/separate/separate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <unordered_map>
#include <utility>

#include "vesselmesh/frames/frames.hpp"
#include "vesselmesh/geometry/closest_point.hpp"

namespace vesselmesh {

namespace {

constexpr double kGap = 0.2;  // separated tubes lie this fraction of the sum of their radii apart
constexpr int kRounds = 8;
constexpr double kStep = 0.25;  // points added along a crossing edge lie this fraction of the radii apart
// Overlapping edge pairs per edge beyond which the vessels form a tangle: 42 to 180 in the tangles the fuzz
// target found (native/fuzz/findings/pipeline/separate-*), at most 7.2 in the shared sets and brava-records.
constexpr std::size_t kTangle = 32;
// Each round's moves are smoothed along their branch over a Gaussian of arc length, σ this many radii.
constexpr double kSmoothing = 2;

// Centerline path lengths between edges, from searches kept per point: crossing_edges asks for every
// pair of overlapping edges, and where the tubes of a star all overlap round its joint (and the
// separate stage has added points every quarter radius along them), a search per pair took over a
// second, minutes under the sanitizers (fuzz finding separate-dense-star-timeout).
class PathLengths {
 public:
  PathLengths(const CenterlineGraph& g, const RoundCones& cones) : g_(g), cones_(cones) {}

  // Whether the centerline path from parameter s of edge e to parameter t of edge f is shorter than
  // `limit`.
  bool near(int32_t e, double s, int32_t f, double t, double limit) {
    if (e == f) return std::abs(s - t) * length(e) < limit;
    for (int i = 0; i < 2; ++i) {
      const double to_end = (i == 0 ? s : 1 - s) * length(e);
      if (to_end >= limit) continue;
      const std::unordered_map<int32_t, double>& reached = from(g_.edges[e][i], limit - to_end);
      for (int j = 0; j < 2; ++j) {
        const auto it = reached.find(g_.edges[f][j]);
        if (it != reached.end() && to_end + it->second + (j == 0 ? t : 1 - t) * length(f) < limit)
          return true;
      }
    }
    return false;
  }

 private:
  struct Search {
    double limit = 0;                            // every point closer than this is in `reached`
    std::unordered_map<int32_t, double> reached;  // point -> its path length from the search's start
  };
  const CenterlineGraph& g_;
  const RoundCones& cones_;
  std::unordered_map<int32_t, Search> searches_;

  // Along the vessel (vessel_lengths), as the cones measure their branches.
  double length(int32_t edge) const { return std::abs(cones_.arc_at(edge, 1) - cones_.arc_at(edge, 0)); }

  // The path lengths from point v to the points closer than `limit` (a Dijkstra search that goes no
  // further), searched again only when a longer limit is asked for.
  const std::unordered_map<int32_t, double>& from(int32_t v, double limit) {
    Search& search = searches_[v];
    if (search.limit >= limit) return search.reached;
    search.limit = limit;
    std::unordered_map<int32_t, double>& reached = search.reached;
    reached.clear();
    using Entry = std::pair<double, int32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    auto reach = [&](int32_t w, double d) {
      if (d >= limit) return;
      auto [it, fresh] = reached.emplace(w, d);
      if (!fresh && it->second <= d) return;
      it->second = d;
      queue.push({d, w});
    };
    reach(v, 0.0);
    while (!queue.empty()) {
      const auto [d, u] = queue.top();
      queue.pop();
      if (d > reached[u]) continue;
      for (int32_t k = g_.offsets[u]; k < g_.offsets[u + 1]; ++k) {
        reach(g_.other(g_.incident[k], u), d + length(g_.incident[k]));
      }
    }
    return search.reached;
  }
};

// How far along branch a from its end at joint j its axis lies all the way within its own radius of a
// tube of branch b: as far as the two tubes overlap from the joint on, as at a fork at a small angle.
// Samples every half radius, at most kMaxSamples per edge (an edge thousands of radii long runs
// beside another vessel's tube only by accident of the tracing), and stops at the first that lies out of
// b's tube. The samples along a from j, with the branches whose tubes hold each, are the same whichever
// branch b is asked about: they are taken once, as far as a question needs them (a star of n branches
// asks n − 1 questions of each).
class JointOverlaps {
 public:
  JointOverlaps(const CenterlineGraph& g, const RoundCones& cones) : g_(g), cones_(cones) {}

  double extent(int32_t a, int32_t b, int32_t j) {
    Walk& walk = walks_[{a, j}];
    for (std::size_t i = 0;; ++i) {
      if (i == walk.samples.size() && !advance(walk, a, j)) return walk.arc;
      const Sample& sample = walk.samples[i];
      if (std::find(sample.near.begin(), sample.near.end(), b) == sample.near.end()) return sample.at;
    }
  }

 private:
  struct Sample {
    double at = 0;              // arc length from the joint
    std::vector<int32_t> near;  // the branches whose tubes hold it
  };
  struct Walk {
    int32_t step = 0;  // the edge, counted from the joint, of the next sample
    int q = 0;         // the next sample's index on that edge
    double arc = 0;    // arc length from the joint to that edge
    std::vector<Sample> samples;
  };
  const CenterlineGraph& g_;
  const RoundCones& cones_;
  std::map<std::array<int32_t, 2>, Walk> walks_;  // (branch, joint) -> its samples so far

  // Takes the walk's next sample; false when it has reached the far end of the branch.
  bool advance(Walk& walk, int32_t a, int32_t j) {
    const Branch& branch = g_.branches[a];
    const bool from_front = branch.points.front() == j;
    const int32_t n = static_cast<int32_t>(branch.edges.size());
    if (walk.step >= n) return false;
    const int32_t edge = branch.edges[from_front ? walk.step : n - 1 - walk.step];
    const RoundCone& k = cones_.cone(edge);
    const bool c0_first = g_.edges[edge][0] == branch.points[from_front ? walk.step : n - walk.step];
    const double length = (k.c1 - k.c0).norm();
    constexpr double kMaxSamples = 256;
    const int samples =
        1 + static_cast<int>(std::min(std::ceil(length / (0.5 * std::min(k.r0, k.r1))), kMaxSamples));
    const double u = static_cast<double>(walk.q) / samples, param = c0_first ? u : 1 - u;
    Sample sample{walk.arc + u * length, {}};
    for (const ConeDistance& d : cones_.within(k.point_at(param), k.radius_at(param)))
      sample.near.push_back(d.branch);
    walk.samples.push_back(std::move(sample));
    if (++walk.q > samples) walk.q = 0, ++walk.step, walk.arc += length;
    return true;
  }
};

// `g` with points added along the edges of `crossing` pairs, kStep times the two radii apart within
// twice kJointReach times the radii of where they cross, so that the moves bend the vessels there rather
// than shift whole edges of a coarse tracing. The tubes stay the same: a round cone is the union of the
// spheres along its axis with linearly varying radii, and so is each piece of it.
CenterlineGraph with_points_where_edges_cross(const CenterlineGraph& g, const RoundCones& cones,
                                              const std::vector<std::array<int32_t, 2>>& crossing) {
  std::vector<std::vector<double>> cuts(g.edges.size());  // per edge, parameters to add points at
  for (const auto& [e, f] : crossing) {
    const auto [s, t] =
        closest_parameters(cones.cone(e).c0, cones.cone(e).c1, cones.cone(f).c0, cones.cone(f).c1);
    const double radii = cones.cone(e).radius_at(s) + cones.cone(f).radius_at(t);
    for (const auto& [edge, at] : {std::pair{e, s}, std::pair{f, t}}) {
      const double length = (cones.cone(edge).c1 - cones.cone(edge).c0).norm(), step = kStep * radii / length;
      // Half a step off where they cross: where two axes meet, the two edges' points must not.
      constexpr int kSteps = static_cast<int>(2 * kJointReach / kStep);
      for (int k = -kSteps; k < kSteps; ++k) {
        const double u = at + (k + 0.5) * step;
        if (u > 0.5 * step && u < 1 - 0.5 * step) cuts[edge].push_back(u);
      }
    }
  }
  CenterlineData d;
  d.points = g.points;
  d.edges.reserve(g.edges.size());
  d.roots = g.roots;
  if (!g.radius_per_edge) d.radius = g.radius;
  // A new point where another point already is (a tracing that doubles back onto its own points) would be
  // merged with it into a loop the vessels do not have: such cuts are left out. Points hash into cells a
  // tenth of a step wide, and a point's partners lie in the cells round its own.
  double smallest = std::numeric_limits<double>::infinity();
  for (const auto& r : g.end_radius) smallest = std::min({smallest, r[0], r[1]});
  const double cell = 0.1 * kStep * smallest;
  using Cell = std::array<int64_t, 3>;
  auto cell_of = [&](const Vec3& p) {
    return Cell{static_cast<int64_t>(std::floor(p.x() / cell)), static_cast<int64_t>(std::floor(p.y() / cell)),
                static_cast<int64_t>(std::floor(p.z() / cell))};
  };
  std::map<Cell, std::vector<Vec3>> taken;
  for (const Vec3& p : g.points) taken[cell_of(p)].push_back(p);
  auto free_at = [&](const Vec3& p) {
    const Cell c = cell_of(p);
    for (int64_t i = -1; i <= 1; ++i)
      for (int64_t j = -1; j <= 1; ++j)
        for (int64_t k = -1; k <= 1; ++k)
          if (const auto it = taken.find({c[0] + i, c[1] + j, c[2] + k}); it != taken.end())
            for (const Vec3& q : it->second)
              if ((q - p).norm() < cell) return false;
    return true;
  };
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    std::vector<double>& at = cuts[e];
    std::sort(at.begin(), at.end());
    const auto [a, b] = g.edges[e];
    const auto [ra, rb] = g.end_radius[e];
    // Cuts of two crossing pairs that fall closer together than a tenth of a step are one.
    const double close = 0.1 * kStep * std::min(ra, rb) / (g.points[b] - g.points[a]).norm();
    int32_t from = a;
    double last = 0;
    for (double u : at) {
      if (u - last < close) continue;
      const Vec3 p = g.points[a] + u * (g.points[b] - g.points[a]);
      if (!free_at(p)) continue;
      taken[cell_of(p)].push_back(p);
      d.points.push_back(p);
      if (!g.radius_per_edge) d.radius.push_back(ra + u * (rb - ra));
      const int32_t point = static_cast<int32_t>(d.points.size()) - 1;
      d.edges.push_back({from, point});
      if (g.radius_per_edge) d.edge_radius.push_back(ra);
      from = point, last = u;
    }
    d.edges.push_back({from, b});
    if (g.radius_per_edge) d.edge_radius.push_back(ra);
  }
  CenterlineGraph refined = build_graph(d);
  refined.report = g.report;
  return refined;
}

// crossing_edges of the overlapping pairs `overlapping` (RoundCones::overlapping_edges).
std::vector<std::array<int32_t, 2>> crossing_among(const CenterlineGraph& g, const RoundCones& cones,
                                                   const std::vector<std::array<int32_t, 2>>& overlapping) {
  if (overlapping.empty()) return {};
  JointOverlaps joint_overlaps(g, cones);
  std::map<std::array<int32_t, 3>, double> extent;  // joint_overlaps.extent(a, b, j), once each
  // Whether parameter s of edge e lies within the overlap of its branch with branch b from joint j, as a
  // fork's: within `reach` of j along its branch, or on an overlap that ends within twice that (the tubes
  // of a fork at a small angle part by themselves; tubes that run on overlapping side by side do not).
  auto overlaps_from_joint = [&](int32_t e, double s, int32_t b, int32_t j, double reach) {
    const int32_t a = cones.cone(e).branch;
    const double at = cones.arc_at(e, s);
    const double from_j = g.branches[a].points.front() == j ? at : cones.branch_length(a) - at;
    if (from_j > 2 * reach) return false;
    auto [it, fresh] = extent.emplace(std::array<int32_t, 3>{a, b, j}, 0.0);
    if (fresh) it->second = joint_overlaps.extent(a, b, j);
    return from_j <= it->second && (from_j <= reach || it->second <= 2 * reach);
  };
  PathLengths paths(g, cones);
  std::vector<std::array<int32_t, 2>> out;
  for (const auto& [e, f] : overlapping) {
    const RoundCone& k = cones.cone(e);
    const RoundCone& l = cones.cone(f);
    const auto [s, t] = closest_parameters(k.c0, k.c1, l.c0, l.c1);
    const double reach = kJointReach * (k.radius_at(s) + l.radius_at(t));
    if (paths.near(e, s, f, t, reach)) continue;
    bool from_joint = false;
    const Branch& a = g.branches[k.branch];
    const Branch& b = g.branches[l.branch];
    for (int32_t j : {a.points.front(), a.points.back()})
      if (k.branch != l.branch && (j == b.points.front() || j == b.points.back())) {
        // The joint's reach: that of the pair's tubes or of its widest tube (a soma's), as the tile's is.
        const double joint_reach = std::max(reach, kJointReach * g.radius[j]);
        from_joint = from_joint || (overlaps_from_joint(e, s, l.branch, j, joint_reach) &&
                                    overlaps_from_joint(f, t, k.branch, j, joint_reach));
      }
    if (!from_joint) out.push_back({e, f});
  }
  return out;
}

// Each point's move averaged with its branch's neighbours' over a Gaussian of arc length (σ kSmoothing
// radii; joints stay). Where several pairs ask neighbouring points to move, each takes the largest move
// asked of it, and points a fortieth of a radius apart could move a radius apart, in different
// directions: the axis zigzagged, and the tiling made a corner patch of it (brava-records BH0009).
// A move's own fade is several radii long, and keeps its shape (docs/pipeline.md: the widths tried).
void smooth_along_branches(const CenterlineGraph& h, const RoundCones& cones, std::vector<Vec3>& move) {
  std::vector<Vec3> smoothed = move;
  for (std::size_t b = 0; b < h.branches.size(); ++b) {
    const std::vector<int32_t>& points = h.branches[b].points;
    const auto bi = static_cast<int32_t>(b);
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (h.degree(points[i]) > 2) continue;
      const double at = cones.arc_at_point(bi, static_cast<int32_t>(i));
      const double sigma = kSmoothing * h.radius[points[i]];
      Vec3 sum = Vec3::Zero();
      double weights = 0;
      auto add = [&](std::size_t j) {
        const double d = cones.arc_at_point(bi, static_cast<int32_t>(j)) - at;
        if (std::abs(d) > 3 * sigma) return false;
        const double w = std::exp(-0.5 * d * d / (sigma * sigma));
        sum += w * move[points[j]], weights += w;
        return true;
      };
      for (std::size_t j = i; j < points.size() && add(j); ++j) {
      }
      for (std::size_t j = i; j-- > 0 && add(j);) {
      }
      smoothed[points[i]] = sum / weights;
    }
  }
  move = std::move(smoothed);
}

}  // namespace

std::vector<std::array<int32_t, 2>> crossing_edges(const CenterlineGraph& g, const RoundCones& cones,
                                                   double gap) {
  return crossing_among(g, cones, cones.overlapping_edges(gap));
}

// The pairs of edges to move apart, of `near` (crossing_edges within kGap): those that cross (the pairs
// crossing_edges without a gap gives, taken from `near` rather than searched again), and those where one
// of them lies within the reach of a joint at an end of its branch and the other does not: a
// joint's patch is the hull of its squares and bulges out of its tubes, onto a vessel passing by
// (records.swc, brava-bg0003's raw twin: a vessel 5 % of a radius from joint 430's tubes).
std::vector<std::array<int32_t, 2>> to_separate(const CenterlineGraph& g, const RoundCones& cones,
                                                const std::vector<std::array<int32_t, 2>>& near) {
  std::vector<std::array<int32_t, 2>> out;
  for (const auto& [e, f] : near)
    if (cones.tubes_overlap(e, f)) out.push_back({e, f});
  auto near_joint = [&](const RoundCone& k, double s) {
    const Branch& b = g.branches[k.branch];
    for (int32_t j : {b.points.front(), b.points.back()})
      if (g.degree(j) > 2 && (g.points[j] - k.point_at(s)).norm() < kJointReach * g.radius[j]) return true;
    return false;
  };
  for (const auto& ef : near) {
    const RoundCone& k = cones.cone(ef[0]);
    const RoundCone& l = cones.cone(ef[1]);
    const auto [s, t] = closest_parameters(k.c0, k.c1, l.c0, l.c1);
    if (near_joint(k, s) != near_joint(l, t)) out.push_back(ef);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Separation separate_crossings(const CenterlineGraph& g, const RoundCones& input_cones) {
  Separation out{g};
  // A tangle in the input already (below) is left at once, its pairs counted no further: points added every
  // quarter radius round each of its crossings made the graph several times as large and the search over it
  // quadratic, and each pair was kept (a cloud of 20,000 points within one radius, as one branch: 200 million
  // pairs, 223 s).
  const std::size_t tangle = kTangle * g.edges.size();
  const std::vector<std::array<int32_t, 2>> overlapping = input_cones.overlapping_edges(kGap, tangle);
  if (overlapping.size() > tangle) {
    out.crossings = out.left = static_cast<int64_t>(overlapping.size());
    out.tangle = true;
    return out;
  }
  const std::vector<std::array<int32_t, 2>> in_input =
      to_separate(g, input_cones, crossing_among(g, input_cones, overlapping));
  out.crossings = out.left = static_cast<int64_t>(in_input.size());
  if (in_input.empty()) return out;
  out.graph = with_points_where_edges_cross(g, input_cones, in_input);
  CenterlineGraph& h = out.graph;
  const std::vector<Vec3> start = h.points;
  std::set<std::array<int32_t, 2>> separating;  // pairs of branches (a ≤ b) to move apart
  for (int round = 0; round <= kRounds; ++round) {
    const RoundCones cones(h);
    auto branches = [&](const std::array<int32_t, 2>& ef) {
      const int32_t a = cones.cone(ef[0]).branch, b = cones.cone(ef[1]).branch;
      return std::array<int32_t, 2>{std::min(a, b), std::max(a, b)};
    };
    const std::vector<std::array<int32_t, 2>> overlapping = cones.overlapping_edges(kGap);
    // A tangle, so many vessels through one place that each piece of tube overlaps dozens of others (on
    // the points added every quarter radius), cannot be parted, and the searches would take seconds:
    // the input is left as it is.
    if (overlapping.size() > kTangle * h.edges.size()) {
      out.graph = g;
      out.left = out.crossings;
      out.tangle = true;
      return out;
    }
    const std::vector<std::array<int32_t, 2>> near = crossing_among(h, cones, overlapping);
    const std::vector<std::array<int32_t, 2>> pairs = to_separate(h, cones, near);
    out.left = static_cast<int64_t>(pairs.size());
    for (const auto& ef : pairs) separating.insert(branches(ef));
    // The vessels that have crossed move on until they lie the gap apart; others merely close by stay.
    std::vector<std::array<int32_t, 2>> crossing;
    for (const auto& ef : near)
      if (separating.count(branches(ef))) crossing.push_back(ef);
    if (crossing.empty() || round == kRounds) break;

    std::vector<Vec3> move(h.points.size(), Vec3::Zero());
    // Asks the points of edge e's branch round parameter s of e to move by `m`, fading over `reach`.
    auto push = [&](int32_t e, double s, const Vec3& m, double reach) {
      const int32_t b = cones.cone(e).branch, i = cones.cone(e).index;
      const Branch& branch = h.branches[b];
      auto arc = [&](std::size_t p) { return cones.arc_at_point(b, static_cast<int32_t>(p)); };
      const double at = cones.arc_at(e, s);
      // Both of a long edge's points move, so that the edge itself does.
      const double half = std::max(reach, 2 * std::max(at - arc(i), arc(i + 1) - at));
      auto ask = [&](std::size_t p) {
        const double d = std::abs(arc(p) - at);
        if (d >= half) return false;
        if (h.degree(branch.points[p]) > 2) return true;  // joints stay, and with them their patches
        Vec3& current = move[branch.points[p]];
        // Faded, m is no larger: where several pairs ask a point to move, most asks end here (a dense star
        // spent a quarter of its time on the cosine).
        if (m.squaredNorm() <= current.squaredNorm()) return true;
        const Vec3 wanted = 0.5 * (1 + std::cos(M_PI * d / half)) * m;
        if (wanted.squaredNorm() > current.squaredNorm()) current = wanted;
        return true;
      };
      for (std::size_t p = i + 1; p < branch.points.size() && ask(p); ++p) {
      }
      for (std::size_t p = i + 1; p-- > 0 && ask(p);) {
      }
    };
    for (const auto& [e, f] : crossing) {
      const RoundCone& k = cones.cone(e);
      const RoundCone& l = cones.cone(f);
      const auto [s, t] = closest_parameters(k.c0, k.c1, l.c0, l.c1);
      const double re = k.radius_at(s), rf = l.radius_at(t);
      const Vec3 between = k.point_at(s) - l.point_at(t);
      // A little past the gap that crossing_edges looks for, so that the next round finds them apart.
      const double gap = 1.1 * kGap * (std::max(k.r0, k.r1) + std::max(l.r0, l.r1));
      const double apart = between.norm(), short_by = re + rf + gap - apart;
      if (short_by <= 0) continue;
      // Away from f; across both axes where e's axis passes through f's.
      Vec3 away = between / apart;
      if (!(apart > 1e-9 * (re + rf))) {
        away = (k.c1 - k.c0).cross(l.c1 - l.c0);
        away = away.norm() > 0 ? Vec3(away.normalized()) : any_perpendicular(k.c1 - k.c0);
      }
      // Equal shares of their radii; but a branch that hooks back through its joint's own tubes moves
      // alone: they, moved close to their joint, which stays, would kink there (fixture
      // `thin_hook_through_its_fat_joint`).
      const int32_t hook = cones.coming_back_of(e, f, kGap);
      const double share_e = hook == e ? 1.0 : hook == f ? 0.0 : re / (re + rf);
      push(e, s, share_e * short_by * away, kJointReach * (re + rf));
      push(f, t, -(1 - share_e) * short_by * away, kJointReach * (re + rf));
    }
    smooth_along_branches(h, cones, move);
    for (std::size_t p = 0; p < h.points.size(); ++p) h.points[p] += move[p];
  }
  for (std::size_t p = 0; p < h.points.size(); ++p)
    if (h.points[p] != start[p]) {
      out.moved_points += 1;
      out.largest_move = std::max(out.largest_move, (h.points[p] - start[p]).norm() / h.radius[p]);
    }
  return out;
}

}  // namespace vesselmesh
