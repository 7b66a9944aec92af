#include "vesselmesh/summary.hpp"

#include <algorithm>
#include <limits>
#include <nlohmann/json.hpp>

#include "vesselmesh/geometry/round_cones.hpp"
#include "vesselmesh/separate/separate.hpp"

namespace vesselmesh {

std::string summary_json(const CenterlineGraph& g, int indent) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& p : g.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  double rmin = std::numeric_limits<double>::infinity(), rmax = 0.0;
  for (const auto& ends : g.end_radius)
    for (double x : ends) rmin = std::min(rmin, x), rmax = std::max(rmax, x);
  const NormalisationReport& r = g.report;
  nlohmann::ordered_json j;
  j["points"] = g.points.size();
  j["edges"] = g.edges.size();
  j["components"] = g.components;
  j["branches"] = g.branches.size();
  j["joints"] = g.joints();
  j["terminals"] = g.terminals();
  j["max_degree"] = g.max_degree();
  j["loops"] = g.loops;
  j["radius"] = {{"min", rmin}, {"max", rmax}, {"per", g.radius_per_edge ? "edge" : "point"}};
  j["bbox"] = {{"min", {lo.x(), lo.y(), lo.z()}}, {"max", {hi.x(), hi.y(), hi.z()}}};
  j["normalisation"] = {{"input_points", r.input_points},       {"input_edges", r.input_edges},
                        {"merged_points", r.merged_points},     {"zero_length_edges", r.zero_length_edges},
                        {"duplicate_edges", r.duplicate_edges}, {"isolated_points", r.isolated_points},
                        {"snapped_coordinates", r.snapped_coordinates}};
  nlohmann::ordered_json overlaps = nlohmann::ordered_json::array();
  const RoundCones cones(g);
  for (const TubeOverlap& o : tube_overlaps(g, cones, crossing_edges(g, cones)))
    overlaps.push_back({{"at", {o.at.x(), o.at.y(), o.at.z()}},
                        {"radius", o.radius},
                        {"edge_pairs", o.edge_pairs},
                        {"crossing_pairs", o.crossing_pairs}});
  j["overlaps"] = overlaps;
  return j.dump(indent);
}

}  // namespace vesselmesh
