"""Curvature out of the package, checked on analytic surfaces: the estimator's normals, shape
tensors, principal curvatures and directions, and the tessellation's exact curvature, in
libigl's convention (the unit sphere with outward normals has K = H = +1, k1 >= k2)."""

import numpy as np
import pytest

import triwb

# The torus of the ring data set: major radius R, tube radius r.
R, r = 1.0, 0.4
# Rounding of the closed forms the estimator and the principal-frame code evaluate (a few
# hundred units of 2.2e-16 on values of order one).
ROUND = 1e-12
# `hybrid` on the 64 × 32 torus grid: its curvature error there (measured 0.021 on k1 and
# 0.015 on k2 at the worst vertex, about 1 % of 1/r), with half as much again for changes.
TORUS_K_TOL = 0.03
# Principal directions on that grid: measured within 1.4e-3 rad of the meridian and the
# parallel at the worst vertex; 0.01 rad allowed.
TORUS_DIRECTION_TOL = 0.01
# The default sphere's fit: the quartic patches' Gaussian curvature lies within 0.19 of 1 at
# the worst tessellation vertex (measured 0.182 at s = 6) and the mean within 0.09 (0.088).
SPHERE_FIT_K_TOL = 0.2
SPHERE_FIT_H_TOL = 0.1


def unit_rows(a):
    return np.abs(np.linalg.norm(a, axis=1) - 1).max()


def test_estimate_on_the_bare_sphere_is_exact_and_outward_positive():
    V, F = triwb.sphere()
    e = triwb.estimate(V, F)
    assert e["missing"] == 0
    assert np.abs(e["K"] - 1).max() < ROUND
    assert np.abs(e["H"] - 1).max() < ROUND, "H > 0 on a sphere with outward normals"
    assert np.abs(e["k1"] - 1).max() < ROUND and np.abs(e["k2"] - 1).max() < ROUND
    assert (np.einsum("ij,ij->i", e["normals"], V) > 0).all(), "outward normals"
    for d in ("d1", "d2"):
        assert unit_rows(e[d]) < ROUND
        assert np.abs(np.einsum("ij,ij->i", e[d], e["normals"])).max() < ROUND


def test_estimate_on_a_torus_finds_its_principal_frame():
    V, F = triwb.ring(64)
    e = triwb.estimate(V, F)
    u = np.arctan2(V[:, 1], V[:, 0])
    rho = np.hypot(V[:, 0], V[:, 1])
    cos_v = (rho - R) / r
    # Along the tube (the meridian) κ = 1/r; along the parallel κ = cos v / (R + r cos v).
    k_meridian = np.full(len(V), 1 / r)
    k_parallel = cos_v / (R + r * cos_v)
    assert np.abs(e["k1"] - np.maximum(k_meridian, k_parallel)).max() < TORUS_K_TOL
    assert np.abs(e["k2"] - np.minimum(k_meridian, k_parallel)).max() < TORUS_K_TOL
    assert np.abs(e["K"] - e["k1"] * e["k2"]).max() < ROUND
    parallel = np.stack([-np.sin(u), np.cos(u), np.zeros_like(u)], axis=1)
    # k1 is the meridian's everywhere (1/r = 2.5 exceeds every parallel curvature): d1 ⟂ the
    # parallel direction, d2 along it.
    assert np.abs(np.einsum("ij,ij->i", e["d1"], parallel)).max() < TORUS_DIRECTION_TOL
    assert (np.abs(np.einsum("ij,ij->i", e["d2"], parallel)) > np.cos(TORUS_DIRECTION_TOL)).all()
    assert np.abs(np.cross(e["d1"], e["d2"]) - e["normals"]).max() < ROUND, "d2 = n × d1"


def test_estimate_keeps_given_normals_and_marks_dropped_vertices():
    V, F = triwb.sphere()
    V2 = np.vstack([V, [[5.0, 5.0, 5.0]]])  # an unreferenced vertex: dropped by the repair
    e = triwb.estimate(V2, F, normals=np.vstack([V, [[0, 0, 1.0]]]))
    assert e["missing"] == 1
    assert np.isnan(e["normals"][-1]).all() and np.isnan(e["K"][-1])
    assert np.abs(e["normals"][:-1] - V).max() < ROUND


def test_an_unknown_estimator_is_refused_with_the_list():
    V, F = triwb.octa()
    with pytest.raises(triwb.UsageError, match="hybrid"):
        triwb.estimate(V, F, method="bogus")


def test_tessellation_curvature_is_consistent_and_near_the_sphere():
    t = triwb.fit("sphere").tessellate(6)
    assert t["V"].shape[1] == 3 and t["F"].shape[1] == 3
    assert len(t["patch"]) == len(t["F"])
    assert (t["k1"] >= t["k2"]).all()
    assert np.abs(t["K"] - t["k1"] * t["k2"]).max() < ROUND
    assert np.abs(t["H"] - 0.5 * (t["k1"] + t["k2"])).max() < ROUND
    assert np.abs(t["K"] - 1).max() < SPHERE_FIT_K_TOL
    assert np.abs(t["H"] - 1).max() < SPHERE_FIT_H_TOL
    assert unit_rows(t["normals"]) < ROUND and unit_rows(t["d1"]) < ROUND
    assert np.abs(np.einsum("ij,ij->i", t["d1"], t["normals"])).max() < ROUND


def test_tessellation_is_in_the_input_coordinates():
    # A mesh far from the origin and large: the fit works in its own frame, and everything the
    # package gives back is in the input's coordinates and units.
    V, F = triwb.sphere()
    scale, shift = 50.0, np.array([1000.0, -20.0, 3.0])
    fit = triwb.fit(V * scale + shift, F)
    t = fit.tessellate(4)
    radius = np.linalg.norm(t["V"] - shift, axis=1)
    assert np.abs(radius / scale - 1).max() < 0.02
    assert np.abs(t["K"] * scale**2 - 1).max() < 0.3
    assert np.abs(fit.V - (V * scale + shift)).max() < 1e-9
    net_radius = np.linalg.norm(fit.nets[:, 0] - shift, axis=1)
    assert np.abs(net_radius / scale - 1).max() < 1e-9, "patch corners interpolate the vertices"


def test_layout_and_edge_curves_describe_the_nets():
    fit = triwb.fit("octa", curves="optimized")
    lay = fit.layout
    assert lay["form"] == "bezier" and lay["degree"] == 4 and lay["points_per_patch"] == 15
    assert fit.nets.shape == (8 * lay["patches_per_face"], 15, 3)
    E = fit.edges
    assert fit.edge_curves.shape == (len(E), 4, 3) and fit.alphas.shape == (len(E), 2)
    # Each edge curve runs from its first vertex to its second.
    assert np.abs(fit.edge_curves[:, 0] - fit.V[E[:, 0]]).max() < ROUND
    assert np.abs(fit.edge_curves[:, 3] - fit.V[E[:, 1]]).max() < ROUND
    assert fit.g1()["max"] < 1e-9
    again = fit.g1(samples=17)
    assert again["max"] < 1e-9 and again["max"] >= 0


# A noisy unit sphere (level 5, edges about 0.06): uniform noise of ±NOISE per coordinate,
# about 0.08 edge lengths. The wide balls of `radius=4` average it: measured |H − 1| RMS 0.050
# (as the default does, which measures the mesh as noisy and hands it to `multiscale`); 0.15
# allowed.
NOISE = 0.005
NOISY_SPHERE_H_TOL = 0.15


def test_estimate_with_a_radius_averages_noise_and_refuses_a_bad_radius():
    V, F = triwb.sphere(5)
    rng = np.random.default_rng(7)
    V = V + rng.uniform(-NOISE, NOISE, V.shape)
    e = triwb.estimate(V, F, radius=4.0)
    assert e["missing"] == 0
    rms = np.sqrt(np.mean((e["H"] - 1) ** 2))
    assert rms < NOISY_SPHERE_H_TOL, rms
    assert any("jet-ball" in n for n in e["notes"]), e["notes"]
    for bad in (0.0, -1.0, float("nan")):
        with pytest.raises(Exception, match="radius"):
            triwb.estimate(V, F, radius=bad)
