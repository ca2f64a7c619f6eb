"""Scale-out: the Dask example on the fixture store, with a 2-worker LocalCluster, gives the
rows of `close eval --json`."""

import importlib.util
import json

import pytest

# Dask is the user's, not a dependency: without it these tests skip (CI installs it and
# fails on any skip).
distributed = pytest.importorskip("distributed")

import close
from conftest import ROOT, STORE, cli_json


def example():
    spec = importlib.util.spec_from_file_location("dask_eval", ROOT / "examples" / "dask_eval.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=":0") as cluster:
        with distributed.Client(cluster) as client:
            yield client


def test_the_dask_example_equals_close_eval(client):
    expected = cli_json("eval", STORE)
    assert expected["samples"], "the fixture store has rows"
    with distributed.get_task_stream(client) as tasks:
        report = example().evaluate_on(client, [str(STORE)])
    assert report == expected
    # The work was shared: both workers ran some of it.
    assert len({t["worker"] for t in tasks.data}) == 2


def test_the_example_runs_as_a_script(tmp_path):
    out = tmp_path / "report.json"
    assert example().main([str(STORE), "--workers", "2", "--json", str(out)]) == 0
    assert json.loads(out.read_text()) == cli_json("eval", STORE)


def test_store_actions_are_the_evaluated_folds():
    store = close.vrfolding.open(STORE)
    rows = cli_json("eval", STORE)["samples"]
    scored = [r for r in rows if not r.get("dropped") and not r.get("error")]
    assert len(store) == len(scored)
    assert store.dropped == sum(1 for r in rows if r.get("dropped"))
    assert {f"{a.meta['video_id']}/fold{a.meta['fold']}" for a in store} == {r["name"] for r in scored}
