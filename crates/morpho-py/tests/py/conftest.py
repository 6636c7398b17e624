"""Shared helpers: the `morpho` command (MORPHO_CLI) and the staged data (MORPHO_DATA)."""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest


def _cli_path():
    p = os.environ.get("MORPHO_CLI")
    if p:
        return p
    here = pathlib.Path(__file__).resolve()
    return str(here.parents[4] / "target" / "release" / "morpho")


@pytest.fixture
def cli(tmp_path):
    """Runs `morpho ARGS… --report R.json` and returns the report (fails unless exit 0)."""

    def run(*args, code=0):
        rep = tmp_path / f"report{len(list(tmp_path.glob('report*')))}.json"
        r = subprocess.run([_cli_path(), *map(str, args), "--report", str(rep)],
                           capture_output=True, text=True)
        assert r.returncode == code, f"morpho {args}: exit {r.returncode}\n{r.stderr}"
        return json.loads(rep.read_text()) if rep.exists() else {}

    return run


@pytest.fixture
def data():
    d = os.environ.get("MORPHO_DATA")
    if not d or not pathlib.Path(d).is_dir():
        pytest.skip("staged data (MORPHO_DATA) not available")
    return pathlib.Path(d)


def write_csv(path, pts, columns=None):
    """Points (and value columns) as a CSV with a header."""
    names = ["x", "y", "z"][: pts.shape[1]]
    cols = [pts[:, i] for i in range(pts.shape[1])]
    for k, v in (columns or {}).items():
        names.append(k)
        cols.append(np.asarray(v, dtype=float))
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for row in zip(*cols):
            f.write(",".join(repr(float(v)) for v in row) + "\n")
    return path


def tri_set(t):
    """Triangles as a set of rotations starting at the smallest index (orientation kept)."""
    out = set()
    for a in np.asarray(t).tolist():
        i = a.index(min(a))
        out.add(tuple(a[i:] + a[:i]))
    return out


def simplex_set(t):
    """Simplices (any size) as a set of sorted tuples."""
    return {tuple(sorted(x)) for x in np.asarray(t).tolist()}
