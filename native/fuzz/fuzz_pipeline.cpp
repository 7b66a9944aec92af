// The whole pipeline on small graphs: validate(), build_graph() and mesh_centerline() at levels 0-1 on a
// centerline decoded from the input. The decoding (docs/fuzzing.md) reaches extreme doubles (1e300,
// 1e-300, denormals, 2e8, raw bit patterns) and huge radius ratios in a few bytes:
//
//   byte 0   options: bit 0 SWC mode, bit 1 levels (0/1), bit 2 crossings keep (else separate), bit 3 open
//            caps, bits 4-5 fit (onto, inward, none, none), bits 6-7 refinement (uniform, curvature,
//            dihedral, curvature)
//   SWC mode: the rest of the input is an SWC file (parse_swc).
//   Otherwise:
//   byte 1   points: 2 + b % 31 (2..32)
//   byte 2   bit 0 radius per edge (else per point), bits 1-2 extra edges (0..3, loops), bit 3
//            unidirectional sampling, bit 4 curvature, bit 5 point 0 is the root, bit 6 no uniform level
//            (level 1 refines by the chosen method)
//   then per point: x, y, z (and its radius when per point), each a value (below)
//   then per point i >= 1: its parent, b % i (a tree); per extra edge: two points, b % n each
//   then per edge (radius per edge): its radius
//
//   a value is one selector byte s: s < 0xC0 a grid value, (s - 96) / 16 for a coordinate (-6 to 6),
//   (s + 8) / 32 for a radius (0.25 to 6.2), so that plain values give edges at most ~80 radii long;
//   0xC0..0xEF an extreme value from kSpecial; 0xF0..0xF7 a raw little-endian double in the next 8 bytes;
//   0xF8..0xFF the previous point's coordinate (or radius) plus (s - 0xFB) * 1e-7 of it.
//   Bytes past the end read as 0.
//
// Only InputError and SizeLimitError may leave: validate() and build_graph() refusing an input, or the
// pipeline refusing a surface over its triangle limit, is fine; anything else
// (another exception, a sanitizer report, a timeout, running out of memory) is a finding, and so are a
// non-finite vertex in the output surface and, with flat caps, a surface that is not a closed manifold
// with one piece per component (the pipeline's own check).
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "fuzz_support.hpp"
#include "vesselmesh/pipeline.hpp"
#include "vesselmesh/read/read.hpp"

namespace {

using namespace vesselmesh;

// clang-format off
/// Extreme values, selected by 0xC0 + index (0xC4: 1e-300, 0xCE: 2e8, 0xE6: 1e-3, ...).
constexpr double kSpecial[48] = {
    0.0,     -0.0,     1e300,   -1e300,  1e-300,  -1e-300,  4.9406564584124654e-324 /* least denormal */,
    2.2250738585072009e-308 /* largest denormal */, DBL_MAX, -DBL_MAX, DBL_MIN, 1e308, 1e154, 1e-154,
    2e8,     -2e8,     1e8,     -1e8,    1e15,    -1e15,    1e-15,   1e-8,    1e-12,   1e6,  // 14..23
    1e-6,    1e12,     1e20,    1e-20,   1e100,   1e-100,   1.0 + DBL_EPSILON, 1.0 - DBL_EPSILON / 2,  // 24..31
    0.5,     1.0,      2.0,     3.0,     1e3,     -1e3,     1e-3,    4e9,  // 32..39
    9007199254740992.0 /* 2^53 */, 18014398509481986.0, 2147483648.0, -2147483649.0, 1e-310, 3e-320,
    65504.0, 1e10};  // 40..47
// clang-format on

class Bytes {
 public:
  Bytes(const uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  uint8_t next() { return pos_ < size_ ? data_[pos_++] : 0; }
  std::string_view rest() const {
    return {reinterpret_cast<const char*>(data_) + pos_, size_ - std::min(pos_, size_)};
  }

  /// A value as the header comment says; `previous` is the same quantity of the previous point.
  double value(bool radius, double previous) {
    const uint8_t s = next();
    if (s < 0xC0) return radius ? (s + 8) / 32.0 : (s - 96) / 16.0;
    if (s < 0xF0) return kSpecial[s - 0xC0];
    if (s < 0xF8) {
      uint64_t bits = 0;
      for (int k = 0; k < 8; ++k) bits |= static_cast<uint64_t>(next()) << (8 * k);
      double d;
      std::memcpy(&d, &bits, sizeof d);
      return d;
    }
    return previous + (s - 0xFB) * 1e-7 * previous;
  }

 private:
  const uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

CenterlineData decode(Bytes& in, MeshOptions& options) {
  const uint8_t n_byte = in.next();
  const uint8_t flags = in.next();
  const int n = 2 + n_byte % 31;
  const bool per_edge = flags & 1;
  const int extra = (flags >> 1) & 3;
  if (flags & 8) options.sampling.method = Sampling::unidirectional;
  options.curvature = flags & 16;
  if (flags & 64) options.subdivision.uniform_levels = 0;

  CenterlineData data;
  Vec3 previous(0, 0, 0);
  double previous_radius = 1.0;
  for (int i = 0; i < n; ++i) {
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = in.value(false, previous[k]);
    data.points.push_back(p);
    previous = p;
    if (!per_edge) data.radius.push_back(previous_radius = in.value(true, previous_radius));
  }
  for (int i = 1; i < n; ++i) data.edges.push_back({static_cast<int32_t>(in.next() % i), i});
  for (int e = 0; e < extra; ++e)
    data.edges.push_back({static_cast<int32_t>(in.next() % n), static_cast<int32_t>(in.next() % n)});
  if (per_edge)
    for (std::size_t e = 0; e < data.edges.size(); ++e)
      data.edge_radius.push_back(previous_radius = in.value(true, previous_radius));
  if (flags & 32) data.roots.push_back(0);
  return data;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  const uint8_t mode = in.next();
  MeshOptions options;
  // Large surfaces are a cost, not a fault, and under the sanitizers a 100,000-triangle surface takes
  // seconds: beyond that the limit refuses them.
  options.max_triangles = 100'000;
  options.subdivision.levels = (mode >> 1) & 1;
  options.crossings = mode & 4 ? Crossings::keep : Crossings::separate;
  options.caps = mode & 8 ? Caps::open : Caps::flat;
  constexpr Fit kFits[] = {Fit::onto, Fit::inward, Fit::none, Fit::none};
  options.fit = kFits[(mode >> 4) & 3];
  constexpr Refinement kRefinements[] = {Refinement::uniform, Refinement::curvature, Refinement::dihedral,
                                         Refinement::curvature};
  options.subdivision.method = kRefinements[(mode >> 6) & 3];

  const std::string source = "fuzz-pipeline";
  try {
    const CenterlineData centerline = mode & 1 ? parse_swc(in.rest(), source) : decode(in, options);
    validate(centerline, source);
    const CenterlineGraph graph = build_graph(centerline, source);
    const MeshResult result = mesh_centerline(graph, options);
    for (const Vec3& v : result.mesh.vertices)
      if (!v.allFinite()) {
        std::fprintf(stderr, "==fuzz_pipeline: a non-finite vertex in the output surface\n");
        std::abort();
      }
    // Open caps leave each terminal's square open, and crossings the separate stage left are reported,
    // not faults; with flat caps the surface must close, one piece per component.
    const Verification& v = result.verification;
    if (options.caps == Caps::flat &&
        (!v.topology.closed_manifold() || v.topology.components != v.expected_components)) {
      std::fprintf(stderr, "==fuzz_pipeline: the surface fails its check: %s\n", v.problem().c_str());
      std::abort();
    }
  } catch (const InputError& e) {
    fuzz::refused(e);
  } catch (const SizeLimitError&) {
    // A surface over the triangle limit is refused before the work: what the limit is for.
  }
  return 0;
}
