"""Arrays in: every layout numpy allows is read (and gives the same fit), every bad array is
refused with a message naming the argument and the row, never a crash."""

import numpy as np
import pytest

import triwb


@pytest.fixture(scope="module")
def octa():
    m = triwb.octa()
    return m.V, m.F, m.normals


@pytest.fixture(scope="module")
def reference(octa):
    V, F, N = octa
    return triwb.fit(V, F, normals=N).nets


@pytest.mark.parametrize(
    "convert",
    [
        lambda V, F: (np.asfortranarray(V), F),
        lambda V, F: (np.ascontiguousarray(V.T).T, F),
        lambda V, F: (np.repeat(V, 2, axis=0)[::2], F),
        lambda V, F: (V, F.astype(np.int32)),
        lambda V, F: (V, F.astype(np.uint32)),
        lambda V, F: (V, F.astype(np.uint64)),
        lambda V, F: (V.tolist(), F.tolist()),
        lambda V, F: (V, np.asfortranarray(F)),
    ],
    ids=["fortran", "transposed view", "strided view", "int32", "uint32", "uint64", "lists", "fortran F"],
)
def test_every_layout_gives_the_same_fit(octa, reference, convert):
    V, F, N = octa
    V2, F2 = convert(V, F)
    assert np.array_equal(triwb.fit(V2, F2, normals=N).nets, reference)


def test_float32_positions_are_widened_exactly(octa):
    V, F, N = octa
    V32 = V.astype(np.float32)
    a = triwb.fit(V32, F, normals=N).nets
    b = triwb.fit(V32.astype(np.float64), F, normals=N).nets
    assert np.array_equal(a, b)


def test_arrays_are_not_modified(octa):
    V, F, N = octa
    V0, F0 = V.copy(), F.copy()
    V.setflags(write=False)
    triwb.fit(V, F, normals=N)
    assert np.array_equal(V, V0) and np.array_equal(F, F0)


def bad(V, F, **kw):
    return lambda: triwb.fit(V, F, **kw)


@pytest.mark.parametrize(
    "make,exc,words",
    [
        (lambda V, F: bad(V[:, :2], F), triwb.UsageError, ["V must have shape (n, 3)", "[6, 2]"]),
        (lambda V, F: bad(V, F[:, :2]), triwb.UsageError, ["F must have shape (n, 3)"]),
        (lambda V, F: bad(V[None], F), triwb.UsageError, ["V must have shape"]),
        (lambda V, F: bad(V, F + 6), triwb.UsageError, ["F row 0", "outside 0..6"]),
        (lambda V, F: bad(V, F - 1), triwb.UsageError, ["F row 0", "index -1"]),
        (lambda V, F: bad(np.where(np.arange(18).reshape(6, 3) == 7, np.nan, V), F),
         triwb.UsageError, ["V row 2 is not finite"]),
        (lambda V, F: bad(np.where(np.arange(18).reshape(6, 3) == 0, np.inf, V), F),
         triwb.UsageError, ["V row 0 is not finite"]),
        (lambda V, F: bad(V, F.astype(float)), TypeError, ["F must be an integer array", "float64"]),
        (lambda V, F: bad(V.astype(np.complex128), F), TypeError, ["V must be a float64"]),
        (lambda V, F: bad(V, F, normals=V[:3]), triwb.UsageError, ["normals has 3 rows, V has 6"]),
        (lambda V, F: bad(V, F, shape=np.zeros((6, 3))), triwb.UsageError, ["shape must have shape (n, 3, 3)"]),
        (lambda V, F: bad(V, F, creases=[[0, 0]]), triwb.UsageError, ["creases row 0 joins vertex 0 to itself"]),
        (lambda V, F: bad(V, None), triwb.UsageError, ["F is missing"]),
        (lambda V, F: bad(V, F, resolution=3), triwb.UsageError, ["resolution"]),
        (lambda V, F: bad(V, F, beta=100.0), triwb.UsageError, ["beta", "100"]),
        (lambda V, F: bad(V, F, bogus=1.0), triwb.UsageError, ["unknown argument `bogus`"]),
        (lambda V, F: bad(V, F, scheme="phong", beta=0.3), triwb.UsageError, ["does not read beta"]),
        (lambda V, F: bad(V, F, scheme="nope"), triwb.UsageError, ["unknown surface scheme `nope`"]),
        (lambda V, F: bad(V, F, curves="nope"), triwb.UsageError, ["nope"]),
        (lambda V, F: bad(V, F, solver="nope"), triwb.UsageError, ["unknown solver `nope`"]),
        (lambda V, F: bad(V, F, estimate="nope"), triwb.UsageError, ["nope"]),
        (lambda V, F: bad(V, F, crease_angle=0.0), triwb.UsageError, ["crease_angle"]),
        (lambda V, F: bad(V, F, crease_angle=30.0, no_creases=True), triwb.UsageError, ["exclude"]),
        (lambda V, F: bad(V, F, segments=0), triwb.UsageError, ["segments"]),
    ],
)
def test_bad_input_is_refused_clearly(octa, make, exc, words):
    V, F, _ = octa
    with pytest.raises(exc) as e:
        make(V, F)()
    for w in words:
        assert w in str(e.value), str(e.value)


def test_usage_errors_are_value_errors_and_job_errors_are_not():
    assert issubclass(triwb.UsageError, ValueError)
    assert not issubclass(triwb.WorkbenchError, ValueError)


def test_a_missing_file_is_a_job_error_naming_it(tmp_path):
    missing = tmp_path / "nothing.ply"
    with pytest.raises(triwb.WorkbenchError) as e:
        triwb.fit(missing)
    assert str(missing) in str(e.value)
    with pytest.raises(triwb.WorkbenchError) as e:
        triwb.read_mesh(missing)
    assert str(missing) in str(e.value)


def test_a_malformed_file_names_its_line(tmp_path):
    p = tmp_path / "bad.obj"
    p.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n")
    with pytest.raises(triwb.WorkbenchError) as e:
        triwb.read_mesh(p)
    assert "line 4" in str(e.value), str(e.value)


def test_an_empty_mesh_is_an_error_not_a_crash():
    with pytest.raises((triwb.WorkbenchError, triwb.UsageError)):
        triwb.fit(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64))


def test_a_degenerate_mesh_is_fitted_with_every_fallback_counted():
    # As on the command line: a zero-area face (three collinear corners) gets the fallback
    # patch, and the report says so (never a silent plausible surface).
    fit = triwb.fit([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]], [[0, 1, 2]])
    r = fit.report
    assert [f["reason"] for f in r["fallback_faces"]] == ["zero area"]
    # Three corners at one point are one vertex once the repair welds them: nothing is left
    # to fit, and the error says why.
    with pytest.raises(triwb.WorkbenchError, match="welded"):
        triwb.fit(np.zeros((3, 3)), [[0, 1, 2]])


@pytest.mark.parametrize("samples", [0, 1, 1001, 10**9, 2**64 - 1])
def test_g1_samples_outside_its_range_is_a_usage_error(octa, samples):
    # Fewer than two samples measures nothing (a jump would read as 0); past 1000 the measure
    # costs more than many fits, and 10**9 would not fit in memory. Refused by keyword, before
    # any work: never an abort or a PanicException.
    V, F, N = octa
    with pytest.raises(triwb.UsageError, match="g1_samples"):
        triwb.fit(V, F, g1_samples=samples)


def test_a_pool_of_more_threads_than_any_machine_has_is_a_usage_error(octa):
    V, F, N = octa
    with pytest.raises(triwb.UsageError, match="threads"):
        triwb.fit(V, F, threads=100000)
