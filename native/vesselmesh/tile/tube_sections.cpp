#include "vesselmesh/tile/tube_sections.hpp"

#include <algorithm>
#include <cmath>

namespace vesselmesh {

/// Whether the squares of consecutive sections a and b (normals along the travel, corners within
/// reach_a and reach_b of their centres) reach across each other's planes: b's behind a's, or a's
/// ahead of b's.
bool sections_cross(const Section& a, double reach_a, const Section& b, double reach_b) {
  const double sine = std::sqrt(std::max(0.0, 1 - std::pow(a.normal.dot(b.normal), 2)));
  return a.normal.dot(b.center - a.center) < reach_b * sine || b.normal.dot(b.center - a.center) < reach_a * sine;
}
bool sections_cross(const Section& a, const Section& b, double scale) {
  return sections_cross(a, scale * a.radius, b, scale * b.radius);
}

/// The largest distance of a section's corners from its centre: scale × r, pushed out by the lean
/// against `axis` (see the base mesh's add_section).
double corner_reach(const Section& s, const Vec3& axis, double scale) {
  return scale * s.radius / std::max(std::abs(s.normal.dot(axis)), 0.5);
}

/// For each section, the most sections a chain from the first to it keeps, no two kept in a row
/// crossing (one's square reaching across the other's plane) and none more than kFoldSkip apart; 0
/// where no chain gets. `from` receives each section's predecessor in its chain.
std::vector<int> fold_free_chains(const std::vector<Section>& sections, double scale,
                                  std::vector<std::size_t>& from) {
  const std::size_t n = sections.size();
  std::vector<int> count(n, 0);
  from.assign(n, 0);
  if (n == 0) return count;
  count[0] = 1;
  for (std::size_t i = 1; i < n; ++i)
    for (std::size_t j = i; j-- > (i > kFoldSkip ? i - kFoldSkip : 0);)  // the nearest first, on ties
      if (count[j] + 1 > count[i] && count[j] > 0 && !sections_cross(sections[j], sections[i], scale))
        count[i] = count[j] + 1, from[i] = j;
  return count;
}

/// Moves the inner sections' centres so that the Loop limit surface passes through where they were.
/// Along a tube whose sections each join their neighbours by two edges per corner, the limit of a
/// section's corners moves with 2/3 of its own centre and 1/6 of each neighbour's: a bent centerline
/// would be cut short by about a sixth of the turn, like a cubic B-spline's control polygon. Solving
/// (c[i−1] + 4c[i] + c[i+1])/6 = p[i] (Jacobi sweeps, which halve the error each time) undoes that;
/// end sections (joint squares, caps) stay put, and a ring wraps round. On a jagged centerline the
/// solution swings from side to side: no centre moves by more than a fifth of its radius, and one
/// whose move would fold the tube (its square crossing a neighbour's plane) stays where it was.
void place_for_limit(std::vector<Section>& sections, const std::vector<Vec3>& axis, bool ring, double scale) {
  const std::size_t n = ring ? sections.size() - 1 : sections.size();
  if (n < 3) return;
  std::vector<Vec3> target(n), c(n), next(n);
  for (std::size_t i = 0; i < n; ++i) target[i] = c[i] = sections[i].center;
  const std::size_t first = ring ? 0 : 1, last = ring ? n : n - 1;
  for (int sweep = 0; sweep < 40; ++sweep) {
    next = c;
    for (std::size_t i = first; i < last; ++i)
      next[i] = 1.5 * target[i] - 0.25 * (c[(i + n - 1) % n] + c[(i + 1) % n]);
    std::swap(c, next);
  }
  for (std::size_t i = first; i < last; ++i) {
    const Vec3 move = c[i] - target[i];
    const double most = 0.2 * sections[i].radius;
    sections[i].center = target[i] + (move.norm() > most ? most / move.norm() : 1.0) * move;
  }
  for (std::size_t i = first; i < last; ++i) {
    const std::size_t before = (i + n - 1) % n, after = (i + 1) % n;
    const double here = corner_reach(sections[i], axis[i], scale);
    if (sections_cross(sections[before], corner_reach(sections[before], axis[before], scale), sections[i], here) ||
        sections_cross(sections[i], here, sections[after], corner_reach(sections[after], axis[after], scale)))
      sections[i].center = target[i];
  }
  if (ring) sections.back().center = sections.front().center;
}

/// Keeps the most sections such that no two kept in a row cross (one's square reaching across the
/// other's plane: the tube would fold between them, on a bend tighter than the corners' radius, or where
/// a joint square facing along its chord meets a turning branch). The end sections stay. Dropped one
/// by one against the last kept, a section kept at the bottom of a U-bend, facing down its first leg,
/// had the whole way back up behind its plane: every later section went, and the tube became one
/// straight prism from end to end, through whatever lay beside the bend (brava-records' trunks;
/// fixture u_bend_into_a_joint). Kept sections are at most kFoldSkip apart; where no such chain reaches
/// the last section, sections are dropped one by one as before.
void drop_folds(std::vector<Section>& sections, double scale) {
  const std::size_t n = sections.size();
  if (n <= 2) return;
  std::vector<std::size_t> from;
  const std::vector<int> count = fold_free_chains(sections, scale, from);
  std::vector<Section> kept;
  if (count[n - 1] > 0) {
    for (std::size_t i = n - 1; i > 0; i = from[i]) kept.push_back(sections[i]);
    kept.push_back(sections.front());
    std::reverse(kept.begin(), kept.end());
  } else {
    kept.push_back(sections.front());
    for (std::size_t i = 1; i + 1 < n; ++i)
      if (!sections_cross(kept.back(), sections[i], scale)) kept.push_back(sections[i]);
    while (kept.size() > 1 && sections_cross(kept.back(), sections.back(), scale)) kept.pop_back();
    kept.push_back(sections.back());
  }
  sections = std::move(kept);
}

/// When a branch keeps only its end sections and even these cross (it turns by more than a right angle
/// within a few radii), its terminal ends face along the chord between the two, or along the joint
/// square at its other end: a straight piece with parallel squares cannot fold.
void unfold_ends(std::vector<Section>& sections, bool free_front, bool free_back, double scale) {
  if (sections.size() != 2) return;
  Section &a = sections.front(), &b = sections.back();
  const Vec3 chord = b.center - a.center;
  if (!(chord.norm() > 0) || !sections_cross(a, b, scale)) return;
  if (free_front) a.normal = chord.normalized();
  if (free_back) b.normal = chord.normalized();
  if (sections_cross(a, b, scale) && free_front != free_back)
    (free_front ? a.normal : b.normal) = (free_front ? b : a).normal;
}

}  // namespace vesselmesh
