// vesselmesh_core: the core as a Python module (numpy arrays in, numpy arrays out). Importable by
// /usr/bin/python3 and inside Blender. C++ errors become Python exceptions: InputError (bad input,
// naming the file and place) derives from ValueError; anything else is a RuntimeError.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <map>
#include <optional>
#include <stdexcept>

#include "freed_memory.hpp"
#include "vesselmesh/check/check_mesh.hpp"
#include "vesselmesh/curvature/curvature.hpp"
#include "vesselmesh/error.hpp"
#include "vesselmesh/geometry/round_cones.hpp"
#include "vesselmesh/graph/centerline_graph.hpp"
#include "vesselmesh/mesh/mesh_edges.hpp"
#include "vesselmesh/mesh/mesh_files.hpp"
#include "vesselmesh/option_names.hpp"
#include "vesselmesh/pipeline.hpp"
#include "vesselmesh/read/read.hpp"
#include "vesselmesh/separate/hidden.hpp"
#include "vesselmesh/separate/separate.hpp"
#include "vesselmesh/summary.hpp"
#include "vesselmesh/synth/synth.hpp"

namespace py = pybind11;
using namespace vesselmesh;

namespace {

template <typename T>
py::array_t<T> to_array(const T* data, std::vector<py::ssize_t> shape) {
  py::array_t<T> out(shape);
  if (out.nbytes() > 0) std::memcpy(out.mutable_data(), data, out.nbytes());
  return out;
}

py::array_t<double> points_array(const std::vector<Vec3>& p) {
  return to_array(p.empty() ? nullptr : p.front().data(), {static_cast<py::ssize_t>(p.size()), 3});
}

py::array_t<int32_t> edges_array(const std::vector<Edge>& e) {
  return to_array(e.empty() ? nullptr : e.front().data(), {static_cast<py::ssize_t>(e.size()), 2});
}

py::object optional_vector(const std::vector<double>& v) {
  if (v.empty()) return py::none();
  return to_array(v.data(), {static_cast<py::ssize_t>(v.size())});
}

/// CenterlineData as a dict of numpy arrays; `radius` or `edge_radius` is None, whichever is absent.
py::dict data_dict(const CenterlineData& d) {
  py::dict out;
  out["points"] = points_array(d.points);
  out["radius"] = optional_vector(d.radius);
  out["edges"] = edges_array(d.edges);
  out["edge_radius"] = optional_vector(d.edge_radius);
  out["roots"] = to_array(d.roots.data(), {static_cast<py::ssize_t>(d.roots.size())});
  return out;
}

/// Vertex properties as {name: (V,) float32}.
py::dict property_dict(const std::vector<VertexProperty>& properties) {
  py::dict out;
  for (const VertexProperty& p : properties)
    out[p.name.c_str()] = to_array(p.values.data(), {static_cast<py::ssize_t>(p.values.size())});
  return out;
}

/// The enum value a name stands for; ValueError listing the names otherwise.
template <typename E>
E choice(const char* what, const std::string& name, const std::map<std::string, E>& names) {
  if (const auto it = names.find(name); it != names.end()) return it->second;
  std::string known;
  for (const auto& [n, value] : names) known += (known.empty() ? "'" : ", '") + n + "'";
  throw py::value_error(std::string(what) + " must be one of " + known + ", got '" + name + "'");
}

using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Indices = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;
using Values = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// `array` as int64 indices when it holds integers (any integer dtype, a list of ints, or nothing);
/// InputError naming `what` otherwise, rather than truncating floats or reading booleans as indices.
Indices integer_array(const py::object& array, const char* what, const char* of) {
  const py::array a = py::array::ensure(array);
  const std::string must = std::string(what) + " must hold integer " + of + " indices";
  if (!a) throw InputError("arrays", "", must);
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u' && a.size() > 0)
    throw InputError("arrays", "", must + ", not " + py::str(a.dtype()).cast<std::string>());
  return Indices::ensure(a);
}

CenterlineData data_from_arrays(const Points& points, const py::object& edge_array,
                                const std::optional<Values>& radius, const std::optional<Values>& edge_radius,
                                const std::optional<py::object>& root_array) {
  const Indices edges = integer_array(edge_array, "edges", "point");
  if (points.ndim() != 2 || points.shape(1) != 3) throw InputError("arrays", "", "points must have shape (N, 3)");
  if (edges.ndim() != 2 || edges.shape(1) != 2) throw InputError("arrays", "", "edges must have shape (E, 2)");
  CenterlineData d;
  d.points.resize(points.shape(0));
  std::memcpy(d.points.data(), points.data(), sizeof(double) * 3 * d.points.size());
  d.edges.resize(edges.shape(0));
  auto e = edges.unchecked<2>();
  for (py::ssize_t i = 0; i < edges.shape(0); ++i)
    for (int k = 0; k < 2; ++k) {
      if (e(i, k) < INT32_MIN || e(i, k) > INT32_MAX)
        throw InputError("arrays", "edge " + std::to_string(i), "point index out of range");
      d.edges[i][k] = static_cast<int32_t>(e(i, k));
    }
  auto vector_of = [](const Values& v, const char* name) {
    if (v.ndim() != 1) throw InputError("arrays", "", std::string(name) + " must be one-dimensional");
    return std::vector<double>(v.data(), v.data() + v.shape(0));
  };
  if (radius) d.radius = vector_of(*radius, "radius");
  if (edge_radius) d.edge_radius = vector_of(*edge_radius, "edge_radius");
  if (root_array) {
    const Indices roots = integer_array(*root_array, "roots", "point");
    for (py::ssize_t i = 0; i < roots.size(); ++i) {
      const int64_t r = roots.data()[i];
      if (r < 0 || r >= static_cast<int64_t>(d.points.size()))
        throw InputError("arrays", "",
                         "root index " + std::to_string(r) + " is outside 0.." +
                             std::to_string(static_cast<int64_t>(d.points.size()) - 1));
      d.roots.push_back(static_cast<int32_t>(r));
    }
  }
  validate(d, "arrays");
  return d;
}

py::object json_to_python(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

/// (F,3) faces of any integer type as the core's triangles, each index checked against vertex_count.
/// int32 faces (what the core hands out) are read in place; others are converted to int64 first.
std::vector<Tri> faces_from(const py::object& array, py::ssize_t vertex_count) {
  auto convert = [&](auto faces) {
    using I = typename decltype(faces)::value_type;
    if (!faces) throw InputError("arrays", "", "faces must be an (F, 3) array of integer vertex indices");
    if (faces.ndim() != 2 || faces.shape(1) != 3) throw InputError("arrays", "", "faces must have shape (F, 3)");
    std::vector<Tri> out(faces.shape(0));
    const I* f = faces.data();
    for (py::ssize_t i = 0; i < faces.shape(0); ++i)
      for (int k = 0; k < 3; ++k) {
        const I v = f[3 * i + k];
        if (v < 0 || v >= vertex_count)
          throw InputError("arrays", "face " + std::to_string(i), "vertex index " + std::to_string(v) +
                                                                     " is out of range");
        out[i][k] = static_cast<int32_t>(v);
      }
    return out;
  };
  using Int32 = py::array_t<int32_t, py::array::c_style | py::array::forcecast>;
  return py::isinstance<py::array_t<int32_t>>(array) ? convert(Int32::ensure(array))
                                                     : convert(integer_array(array, "faces", "vertex"));
}

TriMesh mesh_from_arrays(const Points& vertices, const py::object& faces) {
  if (vertices.ndim() != 2 || vertices.shape(1) != 3) throw InputError("arrays", "", "vertices must have shape (V, 3)");
  TriMesh m;
  m.vertices.resize(vertices.shape(0));
  std::memcpy(m.vertices.data(), vertices.data(), sizeof(double) * 3 * m.vertices.size());
  m.faces = faces_from(faces, vertices.shape(0));
  return m;
}

}  // namespace

PYBIND11_MODULE(vesselmesh_core, m) {
  m.doc() = "VesselMesh core: centerline readers, graph, and (later stages) surface meshing.";
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<SizeLimitError>(m, "SizeLimitError", PyExc_RuntimeError);

  m.def(
      "read",
      [](const std::string& path, const std::string& radius_array) {
        ReadOptions options;
        options.radius_array = radius_array;
        CenterlineData d;
        {
          py::gil_scoped_release release;
          d = read_centerline(path, options);
        }
        return data_dict(d);
      },
      py::arg("path"), py::arg("radius_array") = "",
      "Read a centerline file (.swc .vtk .vtp, or a vertices/edges .csv pair) into a dict of numpy arrays:\n"
      "points (N,3) float64, radius (N,) or None, edges (E,2) int32, edge_radius (E,) or None, roots (R,) int32.");

  py::class_<FreedMemoryHold>(
      m, "FreedMemoryHold",
      "While it lives (or until release()), a process that allocates with jemalloc, as\n"
      "Blender does, keeps the pages of freed blocks for reuse instead of handing large\n"
      "ones back at once, which makes the core about twice as fast there. Holds are\n"
      "counted; the last release restores the allocator's settings. Elsewhere it does\n"
      "nothing. Also a context manager.")
      .def(py::init<>())
      .def("release", &FreedMemoryHold::release)
      .def("__enter__", [](FreedMemoryHold& h) -> FreedMemoryHold& { return h; })
      .def("__exit__", [](FreedMemoryHold& h, const py::args&) { h.release(); })
      .def_property_readonly_static(
          "supported", [](const py::object&) { return FreedMemoryHold::supported(); },
          "Whether this process's allocator is one that holding changes.");

  m.def(
      "synthesize",
      [](int64_t sections, int loops, uint64_t seed) {
        SynthOptions o;
        o.sections = sections, o.loops = loops, o.seed = seed;
        CenterlineData d;
        {
          py::gil_scoped_release release;
          d = synthesize_network(o);
        }
        return data_dict(d);
      },
      py::arg("sections") = 2000, py::arg("loops") = 0, py::arg("seed") = 1,
      "A deterministic synthetic arterial network (millimetres), as a dict like read().");

  py::class_<CenterlineGraph>(m, "Graph",
                              "The normalised centerline graph (coincident points merged, zero-length edges\n"
                              "dropped, duplicate edges merged) with its topology.")
      .def(py::init([](const Points& points, const py::object& edges, std::optional<Values> radius,
                       std::optional<Values> edge_radius, std::optional<py::object> roots) {
             return build_graph(data_from_arrays(points, edges, radius, edge_radius, roots), "arrays");
           }),
           py::arg("points"), py::arg("edges"), py::kw_only(), py::arg("radius") = py::none(),
           py::arg("edge_radius") = py::none(), py::arg("roots") = py::none(),
           "Build from points (N,3), edges (E,2) and either radius (N,) or edge_radius (E,).")
      .def_static(
          "read",
          [](const std::string& path, const std::string& radius_array) {
            ReadOptions options;
            options.radius_array = radius_array;
            py::gil_scoped_release release;
            return build_graph(read_centerline(path, options), path);
          },
          py::arg("path"), py::arg("radius_array") = "", "Read a centerline file and build its graph.")
      .def_property_readonly("points", [](const CenterlineGraph& g) { return points_array(g.points); })
      .def_property_readonly("edges", [](const CenterlineGraph& g) { return edges_array(g.edges); })
      .def_property_readonly("radius", [](const CenterlineGraph& g) { return optional_vector(g.radius); },
                             "(N,) the largest radius of each point's edge ends")
      .def_property_readonly(
          "end_radius",
          [](const CenterlineGraph& g) {
            return to_array(g.end_radius.empty() ? nullptr : g.end_radius.front().data(),
                            {static_cast<py::ssize_t>(g.end_radius.size()), 2});
          },
          "(E,2) the radius at each end of each edge")
      .def_property_readonly("roots", [](const CenterlineGraph& g) {
        return to_array(g.roots.data(), {static_cast<py::ssize_t>(g.roots.size())});
      })
      .def_property_readonly("loops", [](const CenterlineGraph& g) { return g.loops; })
      .def_property_readonly("components", [](const CenterlineGraph& g) { return g.components; })
      .def(
          "summary", [](const CenterlineGraph& g) { return json_to_python(summary_json(g, -1)); },
          "The figures of `vesselmesh info --json` as a dict.");

  m.def(
      "mesh",
      [](const CenterlineGraph& graph, int levels, const std::string& sampling, double alpha, double beta,
         double tolerance, double max_step, const std::string& caps, bool curvature, const std::string& method, int uniform_levels,
         double threshold, const std::string& measure, double angle, const std::string& crossings,
         const std::string& fit, int64_t max_triangles, const std::string& verify, int sides) {
        MeshOptions o;
        o.sides = sides;
        o.max_triangles = max_triangles;
        o.verify = choice("verify", verify, verify_names());
        o.crossings = choice("crossings", crossings, crossings_names());
        o.fit = choice("fit", fit, fit_names());
        o.subdivision.levels = levels;
        o.subdivision.method = choice("method", method, refinement_names());
        o.subdivision.uniform_levels = uniform_levels;
        o.subdivision.threshold = threshold;
        o.subdivision.measure = choice("measure", measure, measure_names());
        o.subdivision.angle_degrees = angle;
        o.curvature = curvature;
        o.sampling.method = choice("sampling", sampling, sampling_names());
        o.sampling.alpha = alpha;
        o.sampling.beta = beta;
        o.sampling.tolerance = tolerance;
        o.sampling.max_step = max_step;
        o.caps = choice("caps", caps, caps_names());
        MeshResult r;
        {
          py::gil_scoped_release release;
          r = mesh_centerline(graph, o);
        }
        py::dict out;
        out["vertices"] = points_array(r.mesh.vertices);
        out["faces"] = to_array(r.mesh.faces.empty() ? nullptr : r.mesh.faces.front().data(),
                                {static_cast<py::ssize_t>(r.mesh.faces.size()), 3});
        out["stats"] = json_to_python(stats_json(r, -1));
        out["curvature"] = property_dict(r.mesh.vertex_properties);
        out["transition"] = to_array(r.transition.data(), {static_cast<py::ssize_t>(r.transition.size())});
        out["centerline"] = r.separated ? py::cast(std::move(*r.separated)) : py::none();
        return out;
      },
      py::arg("graph"), py::kw_only(), py::arg("levels") = MeshOptions().subdivision.levels, py::arg("sampling") = "bidirectional",
      py::arg("alpha") = 1.0, py::arg("beta") = 4.0, py::arg("tolerance") = SamplingOptions().tolerance,
      py::arg("max_step") = SamplingOptions().max_step, py::arg("caps") = "flat", py::arg("curvature") = false,
      py::arg("method") = "curvature", py::arg("uniform_levels") = SubdivisionOptions().uniform_levels,
      py::arg("threshold") = SubdivisionOptions().threshold,
      py::arg("measure") = "tube-departure", py::arg("angle") = 160.0, py::arg("crossings") = "separate",
      py::arg("fit") = "onto", py::arg("max_triangles") = MeshOptions().max_triangles,
      py::arg("verify") = "auto", py::arg("sides") = MeshOptions().sides,
      "The vessel surface of a graph: dict with vertices (V,3) float64, faces (F,3) int32 "
      "(counter-clockwise\n"
      "from outside), transition (F,) uint8 (1 for crack-closing triangles of adaptive subdivision), stats\n"
      "(counts and per-stage times) and curvature (with curvature=True: k1, k2, mean, gaussian, rms as (V,)\n"
      "float32 arrays, 1/length, convex positive, the round tubes' own along the vessels and a 2-ring fit at\n"
      "joints and caps, and radius, the local tube radius; else empty). method: 'curvature', 'uniform' or "
      "'dihedral';\n"
      "threshold and measure ('tube-departure', 'rms', 'gaussian', 'abs-gaussian', 'mean', 'abs-mean') for\n"
      "curvature, angle (degrees) for dihedral; the first uniform_levels levels split every triangle.\n"
      "crossings: vessels whose tubes cross away from a joint, 'separate' (moved apart) or 'keep'; centerline\n"
      "is the Graph whose tubes the surface follows where they were moved apart (check against it for the\n"
      "fidelity to the vessels as built), None where nothing moved.\n"
      "fit: which vertices come onto the input's tubes, 'onto' (all), 'inward' (those outside) or 'none'.\n"
      "tolerance: sections further apart than alpha's where a straight piece of tube stays within this\n"
      "fraction of the local radius of the centerline (0: alpha's spacing alone), in pieces of up to\n"
      "max_step radii. sides: round every base section, 4 or 8.\n"
      "Raises SizeLimitError (a RuntimeError), before the work, for a surface over max_triangles, and\n"
      "ValueError for options out of range. stats['verified'] is the surface's own check ('auto': closed\n"
      "manifold, and crossings up to a million triangles, near the joints and caps up to 16 million;\n"
      "'full'; 'topology'): its 'problem' is empty when\n"
      "the surface passes, else says what is wrong.");

  m.def(
      "separate",
      [](const CenterlineGraph& graph) -> py::object {
        HiddenTerminals hidden;
        Separation s;
        {
          py::gil_scoped_release release;
          // As mesh_centerline: the hidden terminal branches go first, then the crossing vessels part.
          hidden = drop_hidden_terminals(graph, RoundCones(graph));
          const CenterlineGraph& input = hidden.dropped > 0 ? hidden.graph : graph;
          s = separate_crossings(input, RoundCones(input));
        }
        if (s.moved_points > 0) return py::cast(std::move(s.graph));
        return hidden.dropped > 0 ? py::cast(std::move(hidden.graph)) : py::none();
      },
      py::arg("graph"),
      "The centerline with its crossing vessels moved apart and the terminal branches hidden inside other\n"
      "vessels' tubes left out, the one mesh(graph) builds round by default (its result's 'centerline'), or\n"
      "None where it leaves the graph as it is: what check() measures a surface against.");

  m.def(
      "check",
      [](const Points& vertices, const py::object& faces, const CenterlineGraph* graph) {
        const TriMesh mesh = mesh_from_arrays(vertices, faces);
        CheckReport report;
        {
          py::gil_scoped_release release;
          report = check_mesh(mesh, graph);
        }
        return json_to_python(report_json(report, -1));
      },
      py::arg("vertices"), py::arg("faces"), py::arg("graph") = nullptr,
      "What `vesselmesh check --json` reports for a surface (radius fidelity when a graph is given).");

  m.def(
      "curvature",
      [](const Points& vertices, const py::object& faces) {
        const TriMesh mesh = mesh_from_arrays(vertices, faces);
        std::vector<VertexProperty> properties;
        {
          py::gil_scoped_release release;
          properties = curvature_properties(estimate_curvature(mesh));
        }
        return property_dict(properties);
      },
      py::arg("vertices"), py::arg("faces"),
      "Per-vertex curvature of a surface by 2-ring quadric fitting: {name: (V,) float32} for k1, k2, mean,\n"
      "gaussian and rms (1/length, convex positive for faces counter-clockwise from outside).");

  m.def(
      "local_radius",
      [](const Points& points, const CenterlineGraph& graph) {
        if (points.ndim() != 2 || points.shape(1) != 3) throw InputError("arrays", "", "points must have shape (N, 3)");
        std::vector<Vec3> p(points.shape(0));
        std::memcpy(p.data(), points.data(), sizeof(double) * 3 * p.size());
        std::vector<double> radius;
        {
          py::gil_scoped_release release;
          radius = local_radius(p, RoundCones(graph));
        }
        return to_array(radius.data(), {static_cast<py::ssize_t>(radius.size())});
      },
      py::arg("points"), py::arg("graph"),
      "(N,) float64: the radius of the graph's tubes nearest each point (of the point of the union of round\n"
      "cones closest to it). Curvature times it shows shape whatever a vessel's size: a straight tube's mean\n"
      "curvature times its radius is 1/2.");

  m.def(
      "edges",
      [](const py::object& faces, int32_t vertex_count) {
        const std::vector<Tri> f = faces_from(faces, vertex_count);
        MeshEdges e;
        {
          py::gil_scoped_release release;
          e = mesh_edges(f, vertex_count);
        }
        const int32_t* corner_edges = e.corner_edges.empty() ? nullptr : e.corner_edges.front().data();
        return py::make_tuple(edges_array(e.edges),
                              to_array(corner_edges, {static_cast<py::ssize_t>(e.corner_edges.size()), 3}));
      },
      py::arg("faces"), py::arg("vertex_count"),
      "The edges of a triangle mesh: (edges (E,2) int32, lower vertex first, sorted; corner_edges (F,3) int32,\n"
      "the edge from each face's corner k to corner k+1), as Blender stores a mesh's edges and loops.");

  m.def(
      "write_mesh",
      [](const std::string& path, const Points& vertices, const py::object& faces,
         const py::object& properties, const py::object& colors, const std::string& material,
         const std::vector<std::string>& comments) {
        TriMesh mesh = mesh_from_arrays(vertices, faces);
        if (!properties.is_none())
          for (const auto& [name, values] : py::cast<py::dict>(properties)) {
            const auto array = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(values);
            if (!array || array.ndim() != 1 || array.shape(0) != vertices.shape(0))
              throw InputError("arrays", "property '" + py::cast<std::string>(name) + "'",
                               "must be one value per vertex, shape (V,)");
            mesh.vertex_properties.push_back(
                {py::cast<std::string>(name), std::vector<float>(array.data(), array.data() + array.shape(0))});
          }
        WriteOptions options;
        options.material = material;
        options.comments = comments;
        if (!colors.is_none()) {
          const py::array given = py::array::ensure(colors);
          if (!given || !given.dtype().is(py::dtype::of<uint8_t>()) || given.ndim() != 2 ||
              (given.shape(1) != 3 && given.shape(1) != 4) || given.shape(0) != vertices.shape(0))
            throw InputError("arrays", "colors", "must be 8-bit sRGB, a uint8 array of shape (V, 3) or (V, 4)");
          const auto rgba = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(given);
          const auto channels = rgba.shape(1);
          options.alpha = channels == 4;
          options.colors.resize(rgba.shape(0), {0, 0, 0, 255});
          for (py::ssize_t v = 0; v < rgba.shape(0); ++v)
            for (py::ssize_t c = 0; c < channels; ++c) options.colors[v][c] = rgba.data()[channels * v + c];
        }
        py::gil_scoped_release release;
        write_mesh(mesh, path, options);
      },
      py::arg("path"), py::arg("vertices"), py::arg("faces"), py::kw_only(),
      py::arg("properties") = py::none(), py::arg("colors") = py::none(), py::arg("material") = "",
      py::arg("comments") = std::vector<std::string>(),
      "Write a triangle mesh by the path's extension (.ply .obj .stl): properties {name: (V,) floats} "
      "become\n"
      "PLY float properties; colors (V,3) or (V,4) uint8 sRGB become PLY uchar red green blue [alpha] and "
      "OBJ\n"
      "`v x y z r g b`; material names an OBJ material written to the .mtl beside it. PLY stores positions "
      "as\n"
      "double where float would merge vertices or flatten faces, OBJ as exact decimals; STL (float only)\n"
      "refuses such a mesh (RuntimeError saying to write PLY or OBJ). comments: lines kept as PLY `comment` "
      "or OBJ\n"
      "`#` lines (STL has no place for them), such as `lost loop: ...` for each of stats['lost_loops'], "
      "which\n"
      "`vesselmesh check` names.");

  m.def(
      "read_mesh",
      [](const std::string& path) {
        TriMesh mesh;
        std::vector<std::string> comments;
        {
          py::gil_scoped_release release;
          mesh = read_mesh(path);
          comments = read_mesh_comments(path);
        }
        py::dict out;
        out["vertices"] = points_array(mesh.vertices);
        out["faces"] = to_array(mesh.faces.empty() ? nullptr : mesh.faces.front().data(),
                                {static_cast<py::ssize_t>(mesh.faces.size()), 3});
        out["properties"] = property_dict(mesh.vertex_properties);
        out["comments"] = comments;
        return out;
      },
      py::arg("path"),
      "Read a .ply, .obj or .stl triangle mesh: dict with vertices (V,3) float64, faces (F,3) int32,\n"
      "properties {name: (V,) float32} (PLY's other vertex properties, colours included) and comments (the\n"
      "PLY header's comment lines or the OBJ's leading # lines, as write_mesh's comments).");

  m.def(
      "surface_distance",
      [](const Points& vertices, const py::object& faces, const Points& to_vertices, const py::object& to_faces,
         const CenterlineGraph& graph) {
        const TriMesh from = mesh_from_arrays(vertices, faces), to = mesh_from_arrays(to_vertices, to_faces);
        SurfaceDistanceReport report;
        {
          py::gil_scoped_release release;
          report = surface_distance(from, to, graph);
        }
        return json_to_python(report_json(report, -1));
      },
      py::arg("vertices"), py::arg("faces"), py::arg("to_vertices"), py::arg("to_faces"), py::arg("graph"),
      "Distance from a surface (sampled at its vertices and face centroids) to another, relative to the local\n"
      "radius of the graph: {'vertices': {...}, 'centroids': {...}}, each with min, median, p95, max, mean, count.");

  m.def(
      "radius_error",
      [](const Points& vertices, const py::object& faces, const CenterlineGraph& graph) {
        const TriMesh mesh = mesh_from_arrays(vertices, faces);
        FidelityReport report;
        {
          py::gil_scoped_release release;
          report = radius_fidelity(mesh, graph);
        }
        return to_array(report.per_vertex.data(), {static_cast<py::ssize_t>(report.per_vertex.size())});
      },
      py::arg("vertices"), py::arg("faces"), py::arg("graph"),
      "(V,) float32: each vertex's signed distance to the union of the centerline's round cones, relative\n"
      "to the local radius (negative: inside, too thin); NaN for end-cap vertices.");
}
