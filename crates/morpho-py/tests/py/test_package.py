"""The installed package: stubs, py.typed, docstrings, README examples."""

import ast
import pathlib
import re

import numpy as np

import morpho


def test_stubs_and_docstrings():
    pkg = pathlib.Path(morpho.__file__).parent
    assert (pkg / "py.typed").exists()
    stub = ast.parse((pkg / "__init__.pyi").read_text())
    names = {n.name for n in ast.walk(stub) if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    for name in morpho.__all__:
        if name != "__version__":
            assert name in names, name
            assert (getattr(morpho, name).__doc__ or "").strip(), name
    assert morpho.FlintTree.approx.__doc__ and morpho._morpho.isosurface.__doc__


def test_readme_examples(tmp_path, monkeypatch):
    """Every ```python block of the README runs."""
    readme = pathlib.Path(__file__).resolve().parents[2] / "README.md"
    blocks = re.findall(r"```python\n(.*?)```", readme.read_text(), re.S)
    assert len(blocks) >= 9
    monkeypatch.chdir(tmp_path)
    env = {"np": np, "morpho": morpho}
    for b in blocks:
        exec(compile(b, str(readme), "exec"), env)
