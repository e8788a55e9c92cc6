"""The sweep from Python: the manifest and the table equal the command line's for the same
grid, run here and on a two-worker Dask cluster."""

import json

import pandas
import pytest

import triwb
import triwb.sweep
from conftest import REPO

GRID = {"data": ["octa", "sphere"], "curves": ["chord", "optimized"], "solver": ["lm", "lbfgs"]}
FLAGS = ["--data", "octa,sphere", "--curves", "chord,optimized", "--solver", "lm,lbfgs"]


def timeless(df):
    """The table without its measured times (they differ between any two runs)."""
    return df.drop(columns=[c for c in df.columns if "time" in c])


@pytest.fixture(scope="module")
def cli_table(experiments, tmp_path_factory):
    out = tmp_path_factory.mktemp("sweep")
    experiments("sweep", *FLAGS, "--output", out)
    return pandas.read_json(out / "results.jsonl", lines=True), json.loads((out / "tasks.json").read_text())


def test_the_manifest_is_the_command_lines(cli_table):
    _, manifest = cli_table
    assert triwb.sweep.manifest(GRID) == manifest


def test_the_table_run_here_is_the_command_lines(cli_table):
    table, _ = cli_table
    ours = triwb.sweep.run(GRID)
    assert len(ours) == 6
    pandas.testing.assert_frame_equal(timeless(ours), timeless(table))


def test_the_table_run_on_two_dask_workers_is_the_command_lines(cli_table):
    distributed = pytest.importorskip("dask.distributed")
    table, _ = cli_table
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        ours = triwb.sweep.run(GRID, client)
        # A task's error crosses the cluster as the package's exception, message intact.
        with pytest.raises(triwb.UsageError, match="no-such-mesh.ply"):
            triwb.sweep.run({"data": ["octa", "/no/such/dir/no-such-mesh.ply"], "curves": "chord"}, client)
    pandas.testing.assert_frame_equal(timeless(ours), timeless(table))


def test_a_mesh_file_task_and_a_bad_grid(tmp_path):
    grid = {"data": [str(REPO / "data/meshes/teapot.ply")], "curves": "chord"}
    (task,) = triwb.sweep.tasks(grid)
    r = triwb.sweep.run_task(grid, task["task"])
    assert r["faces"] > 0 and r["g1_defect_radians"] >= 0
    with pytest.raises(triwb.UsageError, match="betta"):
        triwb.sweep.manifest({"betta": 0.2})
    with pytest.raises(triwb.UsageError, match="nope"):
        triwb.sweep.run_task(GRID, "nope")


def test_merge_refuses_a_missing_task():
    results = [triwb.sweep.run_task(GRID, t["task"]) for t in triwb.sweep.tasks(GRID)[:2]]
    with pytest.raises(triwb.WorkbenchError):
        triwb.sweep.merge(GRID, results)
