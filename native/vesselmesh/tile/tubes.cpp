// The tubes: each tube branch's sections planned between the squares at its ends, then added to the mesh
// with the quads between them and flat caps at its terminals.

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "vesselmesh/error.hpp"
#include "vesselmesh/tile/tiler.hpp"
#include "vesselmesh/tile/tube_sections.hpp"

namespace vesselmesh::tile_detail {

/// Adds the section's four corners. Its plane follows the smoothed tangent, which leans against
/// `axis`, the direction the tube really runs (the polyline's) on a coarse or jagged centerline: each
/// corner is pushed out to the radius from the axis line rather than from the centre, or the tube
/// would be too thin by the cosine of the lean (capped at twice the radius, a 60° lean).
/// `weight`: 1 for a tube's sections, 0 for a joint patch's squares; `bend` and `slope` the axis's there
/// (TubeAxis); `reach` the corners' share of the tubes' corner reach (End::reach).
int32_t Tiler::add_section(const Section& s, const Vec3& axis, double weight, const Vec3& bend,
                           double slope, double reach) {
  const int32_t first = static_cast<int32_t>(mesh_.vertices.size());
  for (int k = 0; k < 4; ++k) {
    const Vec3 offset = s.corner(k, scale() * reach) - s.center;
    const double along = offset.normalized().dot(axis);
    mesh_.vertices.push_back(s.center + offset / std::sqrt(std::max(1.0 - along * along, 0.25)));
    mesh_.axes.push_back({s.center - mesh_.vertices.back(), s.radius, weight, axis, bend, slope});
  }
  mesh_.squares.push_back({first, first + 1, first + 2, first + 3});
  if (++mesh_.sections > opt_.max_sections)
    throw SizeLimitError("more than " + std::to_string(opt_.max_sections) + " sections");
  return first;
}

int32_t Tiler::add_square(const Section& s, double reach) {
  return add_section(s, s.normal, 0.0, Vec3::Zero(), 0, reach);
}

/// Branch b's tube (kind tube) before it joins the mesh: its sections placed for the limit surface, with
/// the axis, bend and slope at each, and the quarter turn k its frames end with. Reads only the branch
/// and the squares at its ends, so that tubes are planned on every core at once.
TubePlan Tiler::plan_tube(int32_t b) const {
  const BranchCurve& c = curves_[b];
  const End* head = head_[b] >= 0 ? &ends_[head_[b]] : nullptr;
  const End* tail = tail_[b] >= 0 ? &ends_[tail_[b]] : nullptr;
  const bool ring = first_point(b) == last_point(b) && !head;
  const double from = head ? head->t : 0.0, to = c.length() - (tail ? tail->t : 0.0);
  SamplingOptions sampling = opt_.sampling;  // the sections in all are counted as they are added
  sampling.max_sections = opt_.max_sections;
  std::vector<double> arcs = sample_branch(c, from, to, sampling);
  if (ring && arcs.size() < 4) arcs = {0.0, c.length() / 3, 2 * c.length() / 3, c.length()};

  TubePlan plan;
  plan.ring = ring;
  std::vector<Section>& sections = plan.sections;
  sections.resize(arcs.size());
  for (std::size_t i = 0; i < arcs.size(); ++i) {
    sections[i].center = c.position(arcs[i]);
    sections[i].radius = c.radius_at(arcs[i]);
    sections[i].normal = c.tangent(arcs[i]);
  }
  if (ring) sections.back().center = sections.front().center;
  if (head) sections.front().normal = head->square.normal;
  if (tail) sections.back().normal = -tail->square.normal;
  if (!ring) {
    drop_folds(sections, scale());
    unfold_ends(sections, !head, !tail, scale());
  }
  const std::size_t m = sections.size() - 1;
  // Where the tube really runs at each section: along the polyline through the centres.
  std::vector<Vec3>& axis = plan.axis;
  axis.resize(m + 1);
  for (std::size_t i = 0; i <= m; ++i)
    axis[i] = (sections[std::min(i + 1, m)].center - sections[i > 0 ? i - 1 : 0].center).normalized();
  // The bend of the axis through the centres (the difference of the unit chords either side over half
  // their length, exact for centres on a circle) and the radius's slope along it, before the centres move
  // for the limit surface to pass through them: the round stage puts the surface on circles about that
  // axis, so this is the shape whose curvature the tube has.
  std::vector<Vec3>& bend = plan.bend;
  std::vector<double>& slope = plan.slope;
  bend.assign(m + 1, Vec3::Zero());
  slope.assign(m + 1, 0.0);
  for (std::size_t i = 0; i <= m; ++i) {
    const std::size_t a = i > 0 ? i - 1 : ring ? m - 1 : 0, b = i < m ? i + 1 : ring ? 1 : m;
    const Vec3 in = sections[i].center - sections[a].center, out = sections[b].center - sections[i].center;
    const double l_in = in.norm(), l_out = out.norm();
    if (l_in + l_out > 0) slope[i] = (sections[b].radius - sections[a].radius) / (l_in + l_out);
    if (l_in > 0 && l_out > 0) bend[i] = 2 * (out / l_out - in / l_in) / (l_in + l_out);
  }
  place_for_limit(sections, axis, ring, scale());
  sections.front().up = head ? head->square.up : any_perpendicular(sections.front().normal);
  const Vec3 first_up = sections.front().up;
  const Vec3* target = tail ? &tail->square.up : ring ? &first_up : nullptr;
  plan.k = transport_frames(sections, target);
  return plan;
}

/// Adds branch b's tube, as planned (plan_tube), to the mesh: its sections' corners and the quads between
/// them, and flat caps at its terminals.
void Tiler::build_tube(int32_t b, const TubePlan& plan) {
  const End* head = head_[b] >= 0 ? &ends_[head_[b]] : nullptr;
  const End* tail = tail_[b] >= 0 ? &ends_[tail_[b]] : nullptr;
  const bool ring = plan.ring;
  const int k = plan.k;
  const std::vector<Section>& sections = plan.sections;
  const std::size_t m = sections.size() - 1;
  // Vertex ids of each section's corners, counter-clockwise about the direction of travel.
  std::vector<std::array<int32_t, 4>> ids(m + 1);
  for (std::size_t i = 0; i <= m; ++i) {
    if (i == 0 && head) {
      for (int j = 0; j < 4; ++j) ids[i][j] = head->first_vertex + j;
    } else if (i == m && ring) {
      for (int j = 0; j < 4; ++j) ids[i][j] = ids[0][((j - k) % 4 + 4) % 4];
    } else if (i == m && tail) {
      // The tail square runs counter-clockwise about its outward normal, against the travel.
      for (int j = 0; j < 4; ++j) ids[i][j] = tail->first_vertex + ((k - j) % 4 + 4) % 4;
    } else {
      // A terminal's end section, whose corners the flat cap joins, keeps the cap's shape.
      const bool cap = !ring && (i == 0 || i == m);
      const int32_t first = add_section(sections[i], plan.axis[i], cap ? 0.0 : 1.0, plan.bend[i], plan.slope[i]);
      for (int j = 0; j < 4; ++j) ids[i][j] = first + j;
    }
  }
  for (std::size_t i = 0; i < m; ++i)
    for (int j = 0; j < 4; ++j)
      mesh_.quads.push_back({ids[i][j], ids[i][(j + 1) % 4], ids[i + 1][(j + 1) % 4], ids[i + 1][j]});
  if (opt_.caps == Caps::flat && !ring) {
    if (!head) mesh_.quads.push_back({ids[0][3], ids[0][2], ids[0][1], ids[0][0]});
    if (!tail) mesh_.quads.push_back({ids[m][0], ids[m][1], ids[m][2], ids[m][3]});
  }
}

}  // namespace vesselmesh::tile_detail
