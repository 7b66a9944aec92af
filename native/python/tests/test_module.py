"""The Python module: readers into numpy arrays, graphs from numpy arrays, errors as exceptions."""
import numpy as np
import pytest

import vesselmesh_core as vm


def test_read_returns_numpy_arrays_with_documented_shapes(project_data):
    data = vm.read(str(project_data / "bifurcation.swc"))
    assert data["points"].shape == (10, 3) and data["points"].dtype == np.float64
    assert data["edges"].shape == (9, 2) and data["edges"].dtype == np.int32
    assert data["radius"].shape == (10,)
    assert data["edge_radius"] is None
    assert list(data["roots"]) == [0]


def test_per_edge_radius_comes_back_as_edge_radius(project_data):
    data = vm.read(str(project_data / "ring_with_tail.vtk"))
    assert data["radius"] is None
    np.testing.assert_allclose(data["edge_radius"], [1.0, 1.0, 0.8, 0.8, 1.2, 1.2])


@pytest.mark.parametrize("name, points, edges, loops", [
    ("bifurcation.swc", 10, 9, 0),
    ("ring_with_tail.vtk", 6, 6, 1),
    ("y_vertices.csv", 4, 3, 0),
    ("y_edges.csv", 4, 3, 0),
    ("two_lines.vtp", 5, 4, 0),
])
def test_every_format_builds_a_graph(project_data, name, points, edges, loops):
    summary = vm.Graph.read(str(project_data / name)).summary()
    assert (summary["points"], summary["edges"], summary["loops"]) == (points, edges, loops)


def test_overlapping_vmtk_lines_merge_into_one_bifurcation(project_data):
    summary = vm.Graph.read(str(project_data / "two_lines.vtp")).summary()
    assert summary["joints"] == 1 and summary["branches"] == 3
    assert summary["normalisation"]["merged_points"] == 3
    assert summary["normalisation"]["duplicate_edges"] == 2


def test_graph_from_numpy_arrays_matches_graph_from_file(project_data):
    data = vm.read(str(project_data / "bifurcation.swc"))
    graph = vm.Graph(data["points"], data["edges"], radius=data["radius"], roots=data["roots"])
    from_file = vm.Graph.read(str(project_data / "bifurcation.swc"))
    np.testing.assert_array_equal(graph.points, from_file.points)
    np.testing.assert_array_equal(graph.edges, from_file.edges)
    assert graph.summary() == from_file.summary()


def test_graph_accepts_lists_and_integer_dtypes():
    graph = vm.Graph([[0, 0, 0], [1, 0, 0], [2, 0, 0]], np.array([[0, 1], [1, 2]], np.int64), radius=[0.1] * 3)
    assert graph.summary()["branches"] == 1


@pytest.mark.parametrize("kwargs, message", [
    (dict(radius=[1.0, -1.0]), "point 1: radius -1"),
    (dict(radius=[1.0, float("nan")]), "point 1: radius is not a finite number"),
    (dict(), "no radius"),
    (dict(radius=[1.0, 1.0], edge_radius=[1.0]), "both per point and per edge"),
])
def test_bad_arrays_raise_input_error_naming_the_element(kwargs, message):
    with pytest.raises(vm.InputError, match=message):
        vm.Graph([[0, 0, 0], [1, 0, 0]], [[0, 1]], **kwargs)


@pytest.mark.parametrize("edges", [np.array([[0.0, 1.0]]), [[0, 1.5]], np.array([[True, False]])])
def test_edges_that_are_not_integers_are_refused_rather_than_truncated(edges):
    with pytest.raises(vm.InputError, match="edges must hold integer point indices"):
        vm.Graph([[0, 0, 0], [1, 0, 0]], edges, radius=[1, 1])


@pytest.mark.parametrize("points, radius, message", [
    ([[0, 0, 0], [1e302, 0, 0]], [1, 1], "point 1: coordinate beyond"),
    ([[0, 0, 0], [2e8, 0, 0]], [1, 1], "edge 0: .* times its radius 1, beyond the 1e\\+07"),
    ([[0, 0, 0], [10, 0, 0]], [1, 1e-300], "point 1: radius 1e-300 is below 1e-12"),
    ([[0, 0, 0], [0, 0, 0]], [1, 1], "every edge joins two points at the same place"),
])
def test_extreme_arrays_are_refused_as_the_command_line_refuses_them(points, radius, message):
    with pytest.raises(vm.InputError, match=message):
        vm.Graph(points, [[0, 1]], radius=radius)


@pytest.mark.parametrize("kwargs, message", [
    (dict(alpha=float("nan")), "alpha"), (dict(alpha=0.0), "alpha"), (dict(alpha=-1.0), "alpha"),
    (dict(alpha=float("inf")), "alpha"), (dict(beta=float("nan")), "beta"), (dict(beta=-1.0), "beta"),
    (dict(tolerance=float("nan")), "tolerance"), (dict(tolerance=-0.01), "tolerance"),
    (dict(max_step=1.0), "max_step"),
    (dict(threshold=float("nan")), "threshold"), (dict(angle=float("nan")), "angle"),
    (dict(max_triangles=0), "max_triangles"), (dict(verify="sometimes"), "verify"),
])
def test_mesh_refuses_options_the_command_line_refuses(project_data, kwargs, message):
    graph = vm.Graph.read(str(project_data / "bifurcation.swc"))
    with pytest.raises(ValueError, match=message):
        vm.mesh(graph, **kwargs)


def test_straight_vessel_takes_fewer_sections_unless_the_tolerance_is_zero():
    # 80 radii straight in points a radius apart: Eq. 1 alone (tolerance 0) puts a section every diameter
    # (41); the sparse default, Eq. 1 steps graded from the ends and pieces of up to 32 radii (15).
    points = np.stack([np.zeros(81), np.zeros(81), np.arange(81.0)], axis=-1)
    graph = vm.Graph(points, np.stack([np.arange(80), np.arange(1, 81)], axis=-1), radius=np.ones(81))
    sparse = vm.mesh(graph, levels=0)["stats"]["sections"]
    assert vm.mesh(graph, levels=0, tolerance=0)["stats"]["sections"] > 2 * sparse
    assert vm.mesh(graph, levels=0, max_step=4)["stats"]["sections"] > sparse


def test_mesh_over_the_triangle_limit_stops_before_the_work_saying_what_to_change(project_data):
    graph = vm.Graph.read(str(project_data / "bifurcation.swc"))
    with pytest.raises(vm.SizeLimitError, match="beyond the limit of 500: use fewer levels"):
        vm.mesh(graph, max_triangles=500)
    assert issubclass(vm.SizeLimitError, RuntimeError)


def test_mesh_reports_its_own_check_of_the_surface(project_data):
    graph = vm.Graph.read(str(project_data / "bifurcation.swc"))
    stats = vm.mesh(graph)["stats"]
    verified = stats["verified"]
    assert verified["closed_manifold"] and verified["crossings_checked"]
    assert not verified["crossings_checked_near_joints"]  # only over a million triangles
    assert verified["components"] == verified["expected_components"] == 1
    assert verified["problem"] == ""
    assert stats["small_squares"]  # checked for crossings: every patch has small squares
    unchecked = vm.mesh(graph, verify="topology")["stats"]
    assert not unchecked["verified"]["crossings_checked"]
    assert not unchecked["verified"]["crossings_checked_near_joints"] and not unchecked["small_squares"]


def test_mesh_names_each_loop_it_closes_and_why(project_data):
    graph = vm.Graph.read(str(project_data / "extreme" / "fat_loop_round_a_thin_branch.vtk"))
    stats = vm.mesh(graph)["stats"]
    assert stats["verified"]["genus"] == graph.loops - 1
    assert stats["lost_loops"] == [{"joints": [[-3.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
                                    "why": "the joint patch's hull does not close round its hole"}]
    ring = vm.Graph.read(str(project_data / "ring_with_tail.vtk"))
    assert vm.mesh(ring)["stats"]["lost_loops"] == []


def test_edge_index_out_of_range_is_an_input_error():
    with pytest.raises(vm.InputError, match="edge 0: point index 5"):
        vm.Graph([[0, 0, 0], [1, 0, 0]], [[0, 5]], radius=[1, 1])


def test_input_error_is_a_value_error_naming_file_and_line(tmp_path):
    bad = tmp_path / "bad.swc"
    bad.write_text("1 1 0 0 0 1 -1\n2 1 0 0 x 1 1\n")
    with pytest.raises(ValueError, match=r"bad.swc: line 2"):
        vm.read(str(bad))


def test_missing_file_is_an_input_error(tmp_path):
    with pytest.raises(vm.InputError, match="cannot open|no such file"):
        vm.read(str(tmp_path / "nothing.swc"))


def test_synthesize_is_deterministic_and_has_the_requested_loops():
    a = vm.synthesize(sections=500, loops=2, seed=7)
    b = vm.synthesize(sections=500, loops=2, seed=7)
    np.testing.assert_array_equal(a["points"], b["points"])
    graph = vm.Graph(a["points"], a["edges"], radius=a["radius"])
    assert graph.loops == 2 and graph.components == 1


def test_shared_brava_tree_reads_with_its_published_counts(shared_data):
    summary = vm.Graph.read(str(shared_data / "brava-bg0003" / "BG0003_ColorCoded.CNG.swc")).summary()
    assert (summary["points"], summary["branches"], summary["joints"], summary["loops"]) == (3470, 219, 109, 0)


def test_mesh_returns_a_closed_surface_as_numpy_arrays(project_data):
    graph = vm.Graph.read(str(project_data / "bifurcation.swc"))
    surface = vm.mesh(graph, levels=1)
    assert surface["vertices"].shape[1] == 3 and surface["vertices"].dtype == np.float64
    assert surface["faces"].shape[1] == 3 and surface["faces"].dtype == np.int32
    assert surface["stats"]["triangles"] == len(surface["faces"])
    report = vm.check(surface["vertices"], surface["faces"], graph)
    assert report["closed_manifold"]
    assert report["topology"]["euler_characteristic"] == 2


def test_mesh_of_a_loop_has_genus_one(project_data):
    graph = vm.Graph.read(str(project_data / "ring_with_tail.vtk"))
    surface = vm.mesh(graph, levels=0)
    report = vm.check(surface["vertices"], surface["faces"])
    assert report["topology"]["genus"] == 1


def test_fit_brings_the_crotch_onto_the_tubes_and_can_be_left_out(project_data):
    graph = vm.Graph.read(str(project_data / "bifurcation.swc"))
    # Full squares, as a surface not checked for crossings has them: their hull webs the crotch (small ones
    # hug it, docs/pipeline.md tile step 7), and the fit has a web to bring in.
    fitted, plain = (vm.mesh(graph, levels=2, verify="topology", fit=fit) for fit in ("onto", "none"))
    assert fitted["stats"]["fitted_vertices"] > 0 and plain["stats"]["fitted_vertices"] == 0
    assert np.array_equal(fitted["faces"], plain["faces"])
    furthest_out = [np.nanmax(vm.radius_error(s["vertices"], s["faces"], graph)) for s in (fitted, plain)]
    assert furthest_out[0] <= 0.031 < furthest_out[1]


def test_crossing_vessels_are_moved_apart_unless_kept(project_data):
    graph = vm.Graph.read(str(project_data / "crossing.swc"))
    separated, kept = vm.mesh(graph, levels=1), vm.mesh(graph, levels=1, crossings="keep")
    assert separated["stats"]["separated_points"] > 0 and kept["stats"]["separated_points"] == 0
    assert vm.check(separated["vertices"], separated["faces"], graph)["intersections"]["pairs"] == 0
    crossed = vm.check(kept["vertices"], kept["faces"], graph)["intersections"]
    assert crossed["pairs"] == crossed["pairs_in_overlapping_tubes"] > 0


def test_the_centerline_the_surface_follows_comes_back_where_vessels_were_moved(project_data):
    graph = vm.Graph.read(str(project_data / "crossing.swc"))
    separated = vm.mesh(graph, levels=1)
    moved = separated["centerline"]
    assert moved.points.shape[0] > graph.points.shape[0]  # points added round the crossing
    area_off = [vm.check(separated["vertices"], separated["faces"], g)["fidelity"]["area_off_tubes"]
                for g in (graph, moved)]
    assert area_off[1] < area_off[0]  # the moved vessels are off the file's tubes, not off their own
    assert vm.mesh(graph, levels=1, crossings="keep")["centerline"] is None
    assert vm.mesh(vm.Graph.read(str(project_data / "bifurcation.swc")), levels=1)["centerline"] is None


def test_separate_gives_the_centerline_mesh_builds_round(project_data):
    graph = vm.Graph.read(str(project_data / "crossing.swc"))
    moved = vm.separate(graph)
    built = vm.mesh(graph, levels=0)["centerline"]
    assert np.array_equal(moved.points, built.points)
    assert np.array_equal(moved.edges, built.edges)
    assert vm.separate(vm.Graph.read(str(project_data / "bifurcation.swc"))) is None


def test_separate_leaves_out_the_twigs_mesh_leaves_out():
    # A trunk of radius 1 and a twig wholly inside it: no vessel moves, the twig goes.
    graph = vm.Graph(np.array([[0, 0, -5], [0, 0, 0], [0, 0, 5], [0, 0.45, 1.2]], float),
                     np.array([[0, 1], [1, 2], [1, 3]]), radius=np.array([1, 1, 1, 0.3]))
    left = vm.separate(graph)
    built = vm.mesh(graph, levels=0)
    assert built["stats"]["hidden_terminals"] == 1
    assert len(left.edges) == 2
    assert np.array_equal(left.points, built["centerline"].points)


@pytest.mark.parametrize("kwargs", [dict(sampling="sideways"), dict(caps="round"), dict(levels=7),
                                    dict(method="random"), dict(measure="colour"), dict(threshold=2.0),
                                    dict(angle=-1.0), dict(fit="outward"), dict(crossings="merge")])
def test_mesh_rejects_unknown_options(project_data, kwargs):
    graph = vm.Graph.read(str(project_data / "bifurcation.swc"))
    with pytest.raises((ValueError, vm.InputError)):
        vm.mesh(graph, **kwargs)


def test_check_says_how_far_the_furthest_face_and_the_longest_edge_reach_off_the_tubes(project_data):
    graph = vm.Graph.read(str(project_data / "bifurcation.swc"))
    surface = vm.mesh(graph, levels=2)
    fidelity = vm.check(surface["vertices"], surface["faces"], graph)["fidelity"]
    furthest, longest = fidelity["largest_centroid_offset"], fidelity["longest_edge"]
    assert 0 < furthest["relative"] < 1 and len(furthest["at"]) == 3
    assert 0 < longest["relative"] < 3 and longest["length"] > 0 and len(longest["at"]) == 3
    # A fin from an edge on a child's tube to a point five millimetres off it shows in both.
    vertices, faces = surface["vertices"], surface["faces"]
    i = int(np.argmin(np.linalg.norm(vertices - [1.5, 0.0, 8.0], axis=1)))
    face = next(f for f in faces if i in f)
    j = int(face[(list(face).index(i) + 1) % 3])  # i's neighbour along a face's side
    vertices = np.vstack([vertices, vertices[i] + [0.0, 5.0, 0.0]])
    faces = np.vstack([faces, [[i, j, len(vertices) - 1]]]).astype(np.int32)
    with_fin = vm.check(vertices, faces, graph)["fidelity"]
    assert with_fin["largest_centroid_offset"]["relative"] > furthest["relative"]
    assert with_fin["longest_edge"]["relative"] > longest["relative"]


def test_check_says_how_much_of_the_centerline_has_no_surface_round_it():
    points = [[0, 0, 0], [0, 0, 5], [0, 0, 10], [0, 8, 5]]
    trunk = vm.Graph(points[:3], np.array([[0, 1], [1, 2]], np.int64), radius=[1.0] * 3)
    surface = vm.mesh(trunk, levels=1)
    assert vm.check(surface["vertices"], surface["faces"], trunk)["fidelity"]["missing_axis"]["relative"] == 0
    # The same surface against the trunk with a branch of 8 radii that it lacks.
    branched = vm.Graph(points, np.array([[0, 1], [1, 2], [1, 3]], np.int64), radius=[1.0] * 4)
    missing = vm.check(surface["vertices"], surface["faces"], branched)["fidelity"]["missing_axis"]
    assert 4 < missing["relative"] < 8 and missing["at"][1] > 1


def test_check_rejects_faces_out_of_range():
    with pytest.raises(vm.InputError, match="face 0"):
        vm.check(np.zeros((3, 3)), np.array([[0, 1, 5]]))


def test_radius_error_is_small_on_a_tube_and_nan_on_its_caps(project_data):
    graph = vm.Graph.read(str(project_data / "bifurcation.swc"))
    surface = vm.mesh(graph, levels=2)
    error = vm.radius_error(surface["vertices"], surface["faces"], graph)
    assert error.shape == (len(surface["vertices"]),) and error.dtype == np.float32
    assert np.isnan(error).any() and not np.isnan(error).all()
    assert np.nanmedian(np.abs(error)) < 0.05


def test_mesh_with_curvature_returns_the_five_measures_of_a_tube_and_its_radius(project_data):
    graph = vm.Graph.read(str(project_data / "bifurcation.swc"))
    surface = vm.mesh(graph, levels=3, curvature=True)
    k = surface["curvature"]
    assert sorted(k) == ["gaussian", "k1", "k2", "mean", "radius", "rms"]
    assert all(len(values) == len(surface["vertices"]) for values in k.values())
    assert np.all(k["k1"] >= k["k2"])
    assert np.median(k["mean"]) > 0  # a vessel is convex across its axis
    assert np.allclose(k["radius"], vm.local_radius(surface["vertices"], graph), rtol=1e-6)
    assert vm.mesh(graph, levels=1)["curvature"] == {}


@pytest.mark.parametrize("scale", [1e-3, 1.0, 1e3])
def test_mean_curvature_times_the_local_radius_is_a_half_on_a_tube_of_any_size(scale):
    points = np.c_[np.linspace(0, 40, 21), np.zeros(21), np.zeros(21)] * scale
    graph = vm.Graph(points, np.c_[np.arange(20), np.arange(1, 21)], radius=np.full(21, 2.0 * scale))
    surface = vm.mesh(graph, curvature=True, method="uniform")
    middle = np.abs(surface["vertices"][:, 0] / scale - 20) < 10  # away from the caps
    shape = surface["curvature"]["mean"][middle] * surface["curvature"]["radius"][middle]
    assert np.allclose(surface["curvature"]["radius"][middle], 2.0 * scale, rtol=1e-6)
    assert abs(np.median(shape) - 0.5) < 0.02


@pytest.mark.parametrize("method", ["curvature", "dihedral"])
def test_adaptive_methods_give_fewer_triangles_on_the_uniform_surface(project_data, method):
    graph = vm.Graph.read(str(project_data / "bifurcation.swc"))
    # Before the fit, whose guard reads each surface's own triangles and holds back other moves where the
    # patches' small squares come out onto the tubes (0.08 radii apart on this fixture).
    uniform = vm.mesh(graph, levels=2, method="uniform", fit="none")
    adaptive = vm.mesh(graph, levels=2, method=method, uniform_levels=0, angle=150.0, fit="none")
    assert len(adaptive["faces"]) < len(uniform["faces"])
    assert vm.check(adaptive["vertices"], adaptive["faces"])["closed_manifold"]
    assert adaptive["transition"].shape == (len(adaptive["faces"]),) and adaptive["transition"].any()
    assert not uniform["transition"].any()
    distance = vm.surface_distance(adaptive["vertices"], adaptive["faces"], uniform["vertices"],
                                   uniform["faces"], graph)
    # Adaptive vertices are vertices of the uniform surface, each coordinate rounded to float: one float
    # step of the largest coordinate apart at most, counted in the smallest radius.
    float_step = np.spacing(np.float32(np.abs(uniform["vertices"]).max())) / graph.radius.min()
    assert distance["vertices"]["max"] <= 2 * float_step
    assert 0 < distance["centroids"]["max"] < 0.5  # unsplit triangles are flat chords of it
    assert distance["centroids"]["count"] == len(adaptive["faces"])


def test_threshold_zero_is_uniform(project_data):
    graph = vm.Graph.read(str(project_data / "bifurcation.swc"))
    np.testing.assert_array_equal(vm.mesh(graph, levels=2, threshold=0.0)["faces"],
                                  vm.mesh(graph, levels=2, method="uniform")["faces"])


def test_curvature_of_given_arrays_is_the_fit_and_the_mesh_run_paints_the_tubes_own(project_data):
    graph = vm.Graph.read(str(project_data / "bifurcation.swc"))
    surface = vm.mesh(graph, levels=2, curvature=True)
    again = vm.curvature(surface["vertices"], surface["faces"])
    assert sorted(again) == sorted(set(surface["curvature"]) - {"radius"})  # the surface alone has no tubes
    for name, values in again.items():
        assert values.dtype == np.float32
    # The fork's vessels are straight: a tube's mean curvature is 1/(2r). The mesh run blends the tubes' own
    # curvature in along them (the fit alone speaks only at the joint's squares and the caps).
    radius = surface["curvature"]["radius"]
    fit = np.abs(2 * radius * again["mean"] - 1)
    painted = np.abs(2 * radius * surface["curvature"]["mean"] - 1)
    assert np.median(painted) < np.median(fit)
    assert np.count_nonzero(painted != fit) > len(fit) // 2
    with pytest.raises(vm.InputError, match="face 0"):
        vm.curvature(np.zeros((3, 3)), np.array([[0, 1, 5]]))


def test_edges_join_each_corner_to_the_next_and_count_as_a_closed_surface_needs(project_data):
    surface = vm.mesh(vm.Graph.read(str(project_data / "bifurcation.swc")), levels=1)
    faces = surface["faces"]
    edges, corner_edges = vm.edges(faces, len(surface["vertices"]))
    assert edges.dtype == corner_edges.dtype == np.int32
    assert corner_edges.shape == faces.shape
    assert 2 * len(edges) == faces.size  # closed: every edge has two faces
    following = np.roll(faces, -1, axis=1)
    np.testing.assert_array_equal(edges[corner_edges], np.stack([np.minimum(faces, following),
                                                                 np.maximum(faces, following)], axis=-1))
    with pytest.raises(ValueError, match="face 0"):
        vm.edges(np.array([[0, 1, 5]], dtype=np.int32), 3)


def test_surface_functions_take_faces_of_any_integer_type_and_name_bad_ones(project_data):
    surface = vm.mesh(vm.Graph.read(str(project_data / "bifurcation.swc")), levels=1)
    vertices, faces = surface["vertices"], surface["faces"]
    expected = vm.curvature(vertices, faces)
    for same in (faces.astype(np.int64), faces.astype(np.uint16), faces.tolist()):
        again = vm.curvature(vertices, same)
        assert all(np.array_equal(again[name], expected[name]) for name in expected)
    with pytest.raises(vm.InputError, match="integer vertex indices"):
        vm.curvature(vertices, [["a", "b", "c"]])
    with pytest.raises(vm.InputError, match="shape"):
        vm.check(vertices, faces[:, :2])


def test_holding_freed_memory_is_harmless_where_the_allocator_is_not_jemalloc(project_data):
    assert not vm.FreedMemoryHold.supported  # /usr/bin/python3 allocates with glibc's malloc
    graph = vm.Graph.read(str(project_data / "bifurcation.swc"))
    with vm.FreedMemoryHold():
        held = vm.mesh(graph, levels=1)
    plain = vm.mesh(graph, levels=1)
    np.testing.assert_array_equal(held["faces"], plain["faces"])
