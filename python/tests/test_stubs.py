"""The type stubs and docstrings stay true to the module: every public name of strata, of its
submodules and of their classes appears in the installed stubs (and the stubs name nothing the
module lacks), and every bound function, method and class says what it does."""
import ast
import inspect
import os

import pytest

import strata

MODULES = {"__init__": strata, "io": strata.io, "trajectory": strata.trajectory,
           "odometry": strata.odometry, "sim": strata.sim, "plan": strata.plan,
           "store": strata.store, "align": strata.align, "localize": strata.localize,
           "objects": strata.objects,
           "explore": strata.explore}


def stub_names(name):
    """{top-level name: set of member names (classes) or None} of the installed stub file."""
    path = os.path.join(os.path.dirname(strata.__file__), name + ".pyi")
    assert os.path.isfile(path), f"{path}: stubs are installed with the package"
    with open(path) as f:
        tree = ast.parse(f.read(), path)
    names = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            names[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)} | {
                n.target.id for n in node.body if isinstance(n, ast.AnnAssign)}
        elif isinstance(node, ast.FunctionDef):
            names[node.name] = None
        elif isinstance(node, ast.ImportFrom) and node.module is None:  # from . import io as io
            names.update({a.asname: None for a in node.names if a.asname == a.name})
    return names


def public(names):
    return {n for n in names if not n.startswith("_")}


def members(cls):
    return public(vars(cls))


def test_the_package_is_typed():
    assert os.path.isfile(os.path.join(os.path.dirname(strata.__file__), "py.typed"))


@pytest.mark.parametrize("stub", sorted(MODULES))
def test_stubs_name_every_public_name_and_no_other(stub):
    module = MODULES[stub]
    stubs = stub_names(stub)
    runtime = public(dir(module))
    assert runtime - public(stubs) == set(), f"missing from {stub}.pyi"
    assert public(stubs) - runtime == set(), f"in {stub}.pyi but not in the module"
    for name in runtime:
        obj = getattr(module, name)
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            assert members(obj) == public(stubs[name]), f"{stub}.pyi: {name}'s members"


def documentation(obj):
    """The docstring without pybind11's signature line ("name(arguments) -> result")."""
    lines = (obj.__doc__ or "").strip().splitlines()
    return "\n".join(line for line in lines if not line.startswith(obj.__name__ + "(")).strip()


def bound():
    for module in MODULES.values():
        for name in public(dir(module)):
            obj = getattr(module, name)
            if inspect.ismodule(obj):
                continue
            yield f"{module.__name__}.{name}", obj
            if inspect.isclass(obj):
                for member in members(obj):
                    attribute = inspect.getattr_static(obj, member)
                    if not isinstance(attribute, property):
                        yield f"{module.__name__}.{name}.{member}", getattr(obj, member)


def test_every_bound_function_method_and_class_is_documented():
    undocumented = [name for name, obj in bound() if not documentation(obj)]
    assert undocumented == []
    assert len(list(bound())) > 30, "the walk found the module's functions"
