"""The planar curve problem and the registries, against the command line's answers."""

import json

import numpy as np
import pytest

import triwb

C, S = np.cos(0.3), np.sin(0.3)
PROBLEMS = np.array(
    [
        [C, S, C, -S, 0.5, 0.4],  # a symmetric arc-like problem
        [1.0, 0.0, 1.0, 0.0, 0.0, 0.0],  # a straight line: α = 1 everywhere
        [np.cos(0.5), np.sin(0.5), np.cos(0.2), -np.sin(0.2), -0.3, 0.8],  # an S-curve
    ]
)


def cli_answers(experiments, tmp_path, method):
    lines = [json.dumps({"t0": list(p[:2]), "t1": list(p[2:4]), "k0": p[4], "k1": p[5]}) for p in PROBLEMS]
    (tmp_path / "in.jsonl").write_text("\n".join(lines) + "\n")
    out = experiments("curve", "--input", tmp_path / "in.jsonl", "--curves", method).stdout
    return [json.loads(l)["methods"][method] for l in out.splitlines() if l.strip()]


def strip_times(v):
    if isinstance(v, dict):
        return {k: strip_times(x) for k, x in v.items() if "time" not in k}
    if isinstance(v, list):
        return [strip_times(x) for x in v]
    return v


@pytest.mark.parametrize("method", ["chord", "dbhs", "optimized"])
def test_curve_equals_the_command_line(experiments, tmp_path, method):
    cli = cli_answers(experiments, tmp_path, method)
    for p, theirs in zip(PROBLEMS, cli):
        ours = triwb.curve(p[:2], p[2:4], p[4], p[5], method)
        assert strip_times(ours) == strip_times(theirs)


@pytest.mark.parametrize("solver", [s["name"] for s in triwb.solvers()])
def test_curves_is_curve_row_for_row(solver):
    batch = triwb.curves(PROBLEMS, "optimized", solver=solver)
    assert batch["alpha"].shape == (3, 2) and batch["points"].shape == (3, 4, 2)
    assert batch["converged"].all()
    for i, p in enumerate(PROBLEMS):
        one = triwb.curve(p[:2], p[2:4], p[4], p[5], "optimized", solver=solver)
        assert list(batch["alpha"][i]) == one["alpha"]
        assert batch["points"][i].tolist() == one["points"]
    # The straight line is the chord choice, whatever the solver.
    assert np.allclose(batch["alpha"][1], 1.0, atol=1e-8)


def test_curves_refuses_a_bad_problem_by_row():
    bad = PROBLEMS.copy()
    bad[2, :2] = [2.0, 0.0]
    with pytest.raises(triwb.UsageError, match="problems row 2"):
        triwb.curves(bad)
    with pytest.raises(triwb.UsageError, match="shape"):
        triwb.curves(PROBLEMS[:, :5])


def test_registries_list_what_fit_accepts():
    schemes = triwb.schemes()
    names = [s["name"] for s in schemes]
    assert [s["name"] for s in schemes if s["default"]] == ["shirman-sequin"]
    ss = schemes[names.index("shirman-sequin")]
    assert {p["key"] for p in ss["parameters"]} == {"beta", "c"}
    for p in ss["parameters"]:
        lo, hi = p["range"]
        assert lo <= p["default"] <= hi
    # Every patch scheme fits the octahedron; each parameter at a value inside its range.
    for s in schemes:
        params = {p["key"]: 0.5 * (p["default"] + p["range"][1]) for p in s["parameters"]}
        fit = triwb.fit("octa", scheme=s["name"], **params)
        assert fit.report["scheme"] == s["name"]
        if s["kind"] == "patches":
            assert fit.nets.shape[1] == s["layout"]["points_per_patch"]
    methods = {m["name"]: m for m in triwb.curve_methods()}
    assert {"chord", "dbhs", "optimized"} <= set(methods)
    assert methods["dbhs"]["enumerates_solutions"] and not methods["chord"]["needs_curvature"]
    assert [e["name"] for e in triwb.estimators() if e["default"]] == ["hybrid"]
    assert [s["name"] for s in triwb.solvers() if s["default"]] == ["exact-penalty"]


def test_every_function_has_a_docstring():
    for name in triwb.__all__:
        obj = getattr(triwb, name)
        if callable(obj):
            assert obj.__doc__ and len(obj.__doc__) > 20, name


def test_tweak_t_and_four_ninths_equal_the_command_line(experiments, tmp_path):
    # The same options as the command line's --tweak-t and --four-ninths, and they matter.
    lines = [json.dumps({"t0": list(p[:2]), "t1": list(p[2:4]), "k0": p[4], "k1": p[5]}) for p in PROBLEMS]
    (tmp_path / "in.jsonl").write_text("\n".join(lines) + "\n")
    for method, cli_args, kwargs in [
        ("tweak", ["--tweak-t", "0.3"], {"tweak_t": 0.3}),
        ("piper", ["--four-ninths"], {"four_ninths": True}),
    ]:
        out = experiments("curve", "--input", tmp_path / "in.jsonl", "--curves", method, *cli_args).stdout
        cli = [json.loads(l)["methods"][method] for l in out.splitlines() if l.strip()]
        for p, theirs in zip(PROBLEMS, cli):
            ours = triwb.curve(p[:2], p[2:4], p[4], p[5], method, **kwargs)
            assert strip_times(ours) == strip_times(theirs)
        default = triwb.curve(PROBLEMS[0][:2], PROBLEMS[0][2:4], PROBLEMS[0][4], PROBLEMS[0][5], method)
        chosen = triwb.curve(PROBLEMS[0][:2], PROBLEMS[0][2:4], PROBLEMS[0][4], PROBLEMS[0][5], method, **kwargs)
        assert default["alpha"] != chosen["alpha"], method


def test_tweak_t_outside_its_range_is_a_usage_error():
    with pytest.raises(triwb.UsageError, match="tweak_t"):
        triwb.curve([1.0, 0.0], [1.0, 0.0], 0.0, 0.0, "tweak", tweak_t=1.5)


def test_heightfield_is_required_or_refused_as_on_the_command_line():
    # A Franke height field: the functional Clough–Tocher when asked (and when detected), the
    # parametric one with heightfield=False; the ring is no height field, so True is refused.
    on = triwb.fit("franke1", scheme="clough-tocher", heightfield=True)
    auto = triwb.fit("franke1", scheme="clough-tocher")
    off = triwb.fit("franke1", scheme="clough-tocher", heightfield=False)
    assert any("detected a height field" in line for line in on.log)
    assert np.array_equal(on.nets, auto.nets)
    assert not any("height field" in line for line in off.log)
    assert not np.array_equal(on.nets, off.nets) if on.nets.shape == off.nets.shape else True
    with pytest.raises(triwb.WorkbenchError, match="height field"):
        triwb.fit("ring", scheme="clough-tocher", heightfield=True)
