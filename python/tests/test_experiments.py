"""symembed.run writes what the binary's run writes; load_results reads it; stages() lists what
`symembed stages --options` lists."""

import json
import os

import numpy as np
import pytest
import symembed
from conftest import run_binary, write_config

VARIANTS = "variants:\n  - {name: fewer, set: {pipeline.sampling.count: 120}}\n"

# summary.json members that are measured times or memory, not results.
MEASURED = ("time_total_s", "time_per_shape_s", "time_per_pair_s", "peak_rss_mb")


def files(folder):
    return sorted(os.path.relpath(os.path.join(d, f), folder)
                  for d, _, names in os.walk(folder) for f in names)


@pytest.fixture(scope="module")
def runs(pair, binary, tmp_path_factory):
    """The same two-variant config run by the binary and by symembed.run."""
    tmp = tmp_path_factory.mktemp("runs")
    config = write_config(tmp / "two.yaml", pair.root, {"pipeline.sampling.count": 150},
                          name="two", variants=VARIANTS)
    by_binary, by_python = tmp / "binary", tmp / "python"
    run_binary(binary, "run", config, "--out", by_binary, "--cache", "", "--quiet")
    out, ok = symembed.run(config, by_python, cache="", quiet=True)
    assert out == str(by_python) and ok
    return by_binary, by_python


def test_run_writes_the_binary_folder(runs):
    by_binary, by_python = runs
    assert files(by_python) == files(by_binary)
    for variant in ("base", "fewer"):
        for name in ["pairs.csv", "curve.csv", "failures.csv"] + [
                os.path.join("maps", f) for f in os.listdir(by_binary / variant / "maps")]:
            assert (by_python / variant / name).read_bytes() == (by_binary / variant / name).read_bytes(), name
        ours = json.loads((by_python / variant / "summary.json").read_text())
        theirs = json.loads((by_binary / variant / "summary.json").read_text())
        for key in MEASURED:
            ours.pop(key, None)
            theirs.pop(key, None)
        assert ours == theirs


def test_run_of_listed_variants_runs_only_those(pair, tmp_path):
    config = write_config(tmp_path / "two.yaml", pair.root, {"pipeline.sampling.count": 150},
                          name="two", variants=VARIANTS)
    out, ok = symembed.run(config, tmp_path / "out", variants=["fewer"],
                           set={"pipeline.sampling.seed": 2}, cache="", quiet=True, report=False)
    assert ok
    assert (tmp_path / "out" / "fewer" / "summary.json").exists()
    assert not (tmp_path / "out" / "base").exists()
    assert "seed: 2" in (tmp_path / "out" / "fewer" / "config.yaml").read_text()


def test_load_results_reads_summary_rows_and_curves(runs):
    _, by_python = runs
    results = symembed.load_results(by_python)
    assert list(results["variants"]) == ["base", "fewer"]
    base = results["variants"]["base"]
    summary = json.loads((by_python / "base" / "summary.json").read_text())
    assert base["summary"] == summary
    assert base["pairs"]["source"].dtype.kind == "U"
    assert base["pairs"]["mean_direct"].dtype == np.float64
    assert len(base["pairs"]["source"]) == summary["pairs"]
    curve = base["curve"]
    assert curve["threshold"][0] == 0 and curve["direct"][-1] <= 1
    assert list(results["comparison"]["variant"]) == ["base", "fewer"]
    # A variant folder alone gives that variant.
    assert symembed.load_results(by_python / "fewer")["summary"]["pairs"] == summary["pairs"]
    with pytest.raises(FileNotFoundError):
        symembed.load_results(by_python / "base" / "maps")


def test_load_results_gives_dataframes_with_pandas(runs):
    pandas = pytest.importorskip("pandas")
    _, by_python = runs
    base = symembed.load_results(by_python, frames=True)["variants"]["base"]
    assert isinstance(base["pairs"], pandas.DataFrame)


def test_stages_lists_what_the_binary_lists(binary):
    listed = run_binary(binary, "stages", "--options").stdout.splitlines()
    stages = symembed.stages()
    expected = []  # (kind, name, [(option, text), ...]) from the binary's listing
    for line in listed:
        if not line.startswith(" "):
            kind, name = line.split()[:2]
            expected.append((kind, name, []))
        else:
            option, text = line.strip().split(": ", 1)
            expected[-1][2].append((option, text))
    assert [(s["kind"], s["name"], list(s["options_text"].items())) for s in stages] == expected
    sampling = next(s for s in stages if s["kind"] == "sampling" and s["name"] == "farthest_point")
    assert isinstance(sampling["options"]["count"], int)
    assert all(s["description"] for s in stages)
