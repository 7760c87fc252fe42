"""The public surface: docstrings with examples that run, stubs that match, the version."""

import ast
import doctest
import inspect
import pathlib
import re

import pytest

import envelope
from envelope import _envelope

PUBLIC_FUNCTIONS = [
    "simplify", "verify", "check", "lod", "genus", "load", "save", "demo", "simplify_trimesh",
]


@pytest.mark.parametrize("name", PUBLIC_FUNCTIONS)
def test_every_public_function_has_a_docstring_with_an_example(name):
    doc = inspect.getdoc(getattr(envelope, name))
    assert doc and ">>> " in doc


def test_doctests_pass():
    pytest.importorskip("trimesh")
    result = doctest.testmod(envelope, optionflags=doctest.ELLIPSIS)
    assert result.attempted > 20 and result.failed == 0


def test_all_is_exported():
    for name in envelope.__all__:
        assert hasattr(envelope, name), name


def test_version_is_the_crate_version():
    cargo = pathlib.Path(__file__).parents[2] / "Cargo.toml"
    if not cargo.exists():
        pytest.skip("not run from the repository")
    version = re.search(r'^version = "([^"]+)"', cargo.read_text(), re.M).group(1)
    assert envelope.__version__ == version


def stub_tree():
    return ast.parse((pathlib.Path(envelope.__file__).parent / "_envelope.pyi").read_text())


def test_stubs_list_every_name_of_the_compiled_module():
    names = {
        node.name if isinstance(node, (ast.ClassDef, ast.FunctionDef)) else node.target.id
        for node in stub_tree().body
        if isinstance(node, (ast.ClassDef, ast.FunctionDef, ast.AnnAssign))
    }
    compiled = {n for n in dir(_envelope) if not n.startswith("_")} | {"__version__"}
    assert compiled == names


def test_stub_classes_list_every_attribute():
    for node in stub_tree().body:
        if not isinstance(node, ast.ClassDef) or issubclass(getattr(_envelope, node.name), Exception):
            continue
        stubbed = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        actual = {n for n in dir(getattr(_envelope, node.name)) if not n.startswith("_")}
        assert stubbed == actual, node.name


def test_stub_functions_match_the_compiled_signatures():
    for node in stub_tree().body:
        if isinstance(node, ast.FunctionDef):
            compiled = inspect.signature(getattr(_envelope, node.name))
            stubbed = [a.arg for a in node.args.args + node.args.kwonlyargs]
            assert list(compiled.parameters) == stubbed, node.name


def test_wrappers_pass_every_argument():
    for name in ["simplify", "lod", "genus", "verify", "check", "load", "save"]:
        wrapper = inspect.signature(getattr(envelope, name)).parameters
        compiled = inspect.signature(getattr(_envelope, name)).parameters
        assert list(wrapper) == list(compiled), name
