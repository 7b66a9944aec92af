#include "vesselmesh/separate/hidden.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "vesselmesh/parallel.hpp"

namespace vesselmesh {

namespace {

/// Spheres of a branch's family are looked at this fraction of their radius apart along it.
constexpr double kStep = 0.25;
/// A branch needing more spheres than this is kept without looking (a thin thread along a fat vessel for
/// thousands of its radii is no twig).
constexpr std::size_t kMaxSpheres = 4096;
/// Branches per task where they are looked at on every core at once: each costs a search per sphere.
constexpr std::size_t kBranchesPerTask = 64;

/// Per sphere of branch b's family, kStep radii apart along it (each edge's ends included), the cones of
/// other branches that hold it whole, sorted; nullopt when one has none. The piece of tube between two
/// consecutive spheres is their convex hull, inside a cone (convex) that holds both.
std::optional<std::vector<std::vector<int32_t>>> holders(const CenterlineGraph& g, const RoundCones& cones,
                                                         int32_t b) {
  std::vector<std::vector<int32_t>> out;
  for (int32_t e : g.branches[b].edges) {
    const Vec3 &c0 = g.points[g.edges[e][0]], &c1 = g.points[g.edges[e][1]];
    const double r0 = g.end_radius[e][0], r1 = g.end_radius[e][1];
    const double step = kStep * std::min(r0, r1);
    if (!(step > 0)) return std::nullopt;
    const double pieces = std::ceil((c1 - c0).norm() / step);
    if (static_cast<double>(out.size()) + pieces >= kMaxSpheres) return std::nullopt;
    for (int64_t i = 0; i <= static_cast<int64_t>(pieces); ++i) {
      const double s = pieces > 0 ? static_cast<double>(i) / pieces : 0.0;
      const Vec3 c = c0 + s * (c1 - c0);
      const double r = r0 + s * (r1 - r0);
      std::vector<int32_t> by;
      // A sphere at a joint is held by the spheres of the joint's other branches there, of the same
      // radius where the radius is given per point: a millionth of it is rounding.
      for (const ConeDistance& d : cones.within(c, 0))
        if (d.branch != b && d.distance <= -r * (1 - 1e-6)) by.push_back(d.cone);
      if (by.empty()) return std::nullopt;
      std::sort(by.begin(), by.end());
      out.push_back(std::move(by));
    }
  }
  return out;
}

/// Whether each piece between consecutive spheres lies in one cone that `counts`.
template <class Counts>
bool covered(const std::vector<std::vector<int32_t>>& spheres, Counts&& counts) {
  for (std::size_t i = 0; i + 1 < spheres.size(); ++i) {
    const std::vector<int32_t>&a = spheres[i], &b = spheres[i + 1];
    bool found = false;
    for (std::size_t j = 0, k = 0; j < a.size() && k < b.size() && !found;)
      if (a[j] < b[k]) ++j;
      else if (b[k] < a[j]) ++k;
      else found = counts(a[j]), ++j, ++k;
    if (!found) return false;
  }
  return true;
}

/// The terminal branches of g hidden in others, less those hidden only in branches that are hidden too.
std::vector<char> hidden_branches(const CenterlineGraph& g, const RoundCones& cones) {
  std::vector<std::optional<std::vector<std::vector<int32_t>>>> held(g.branches.size());
  std::vector<char> hidden(g.branches.size(), 0);
  // Joints with a loop of their own (a branch from the joint back to it): with its third branch gone,
  // the loop would be a bare ring whose tube runs through the joint's sphere, a radius its vessels do not
  // have, and folds (tests/data/extreme/joint_wider_than_its_loop.vtk: 166 crossing pairs). Kept whole.
  std::vector<char> ring_at(g.points.size(), 0);
  for (const Branch& branch : g.branches)
    if (branch.points.front() == branch.points.back()) ring_at[branch.points.front()] = 1;
  parallel_for(
      g.branches.size(),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b) {
          const Branch& branch = g.branches[b];
          const int32_t first = branch.points.front(), last = branch.points.back();
          if (first == last || (g.degree(first) == 1) == (g.degree(last) == 1)) continue;  // not from a joint
          const int32_t joint = g.degree(first) == 1 ? last : first;
          if (g.degree(joint) == 3 && ring_at[joint]) continue;
          held[b] = holders(g, cones, static_cast<int32_t>(b));
          hidden[b] = held[b] && covered(*held[b], [](int32_t) { return true; });
        }
      },
      kBranchesPerTask);
  std::vector<char> drop(g.branches.size(), 0);
  for (std::size_t b = 0; b < g.branches.size(); ++b)
    drop[b] = hidden[b] && covered(*held[b], [&](int32_t cone) { return !hidden[cones.cone(cone).branch]; });
  return drop;
}

/// g without the edges of the dropped branches, its roots kept where they remain.
CenterlineGraph without(const CenterlineGraph& g, const std::vector<char>& drop) {
  std::vector<char> keep(g.edges.size(), 1);
  for (std::size_t b = 0; b < g.branches.size(); ++b)
    if (drop[b])
      for (int32_t e : g.branches[b].edges) keep[e] = 0;
  return build_graph(centerline_data(g, keep));
}

/// Rounds of hidden_branches until none is left, the first on `first`, g's cones; `cones_of(kept)` builds
/// those of each graph left. Returns how many branches went.
template <class ConesOf>
int64_t drop_in_rounds(const CenterlineGraph& g, const RoundCones& first, CenterlineGraph& kept,
                       ConesOf&& cones_of) {
  int64_t dropped = 0;
  const CenterlineGraph* current = &g;
  for (std::vector<char> drop = hidden_branches(g, first);
       std::find(drop.begin(), drop.end(), 1) != drop.end(); drop = hidden_branches(kept, cones_of(kept))) {
    dropped += std::count(drop.begin(), drop.end(), 1);
    kept = without(*current, drop);
    current = &kept;
  }
  return dropped;
}

}  // namespace

HiddenTerminals drop_hidden_terminals(const CenterlineGraph& g, const RoundCones& cones) {
  HiddenTerminals out;
  std::optional<RoundCones> next;
  out.dropped = drop_in_rounds(g, cones, out.graph, [&](const CenterlineGraph& kept) -> const RoundCones& {
    return next.emplace(kept);
  });
  return out;
}

int64_t drop_hidden_terminals(const CenterlineGraph& g, std::optional<RoundCones>& cones,
                              CenterlineGraph& kept) {
  return drop_in_rounds(g, *cones, kept,
                        [&](const CenterlineGraph& k) -> const RoundCones& { return cones.emplace(k); });
}

}  // namespace vesselmesh
