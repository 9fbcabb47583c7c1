"""The type stubs (python/flexwing/_native.pyi) cover the extension exactly: every public class,
function, method and property of `flexwing._native` is in the stub with the same kind (property
or method), nothing in the stub is missing from the extension, and every public name has a
docstring in the extension (what `help()` and editors show) that gives units where it returns
physical values. A binding added without its stub fails here."""

from __future__ import annotations

import ast
import re
import inspect
import pathlib

import flexwing
from flexwing import _native

STUB = pathlib.Path(flexwing.__file__).with_name("_native.pyi")


def stub_tree():
    """{class name: {member: "property" | "method"}} and the set of module functions."""
    tree = ast.parse(STUB.read_text())
    classes, functions = {}, set()
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            members = {}
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    if item.name.startswith("_"):
                        continue
                    names = {d.id if isinstance(d, ast.Name) else getattr(d, "attr", "") for d in item.decorator_list}
                    if "property" in names:
                        members[item.name] = "property"
                    elif "setter" not in names:
                        members[item.name] = "method"
                elif isinstance(item, ast.Assign):  # `stepper = FullModel.stepper`
                    for t in item.targets:
                        members[t.id] = "method"
            classes[node.name] = members
        elif isinstance(node, ast.FunctionDef):
            functions.add(node.name)
    return classes, functions


def runtime_tree():
    classes, functions = {}, set()
    for name, obj in vars(_native).items():
        if name.startswith("_"):
            continue
        if inspect.isclass(obj):
            members = {}
            for m, v in vars(obj).items():
                if m.startswith("_"):
                    continue
                members[m] = "property" if inspect.isdatadescriptor(v) else "method"
            classes[name] = members
        elif callable(obj):
            functions.add(name)
    return classes, functions


def test_the_stub_lists_every_class_function_method_and_property():
    stub_classes, stub_functions = stub_tree()
    classes, functions = runtime_tree()
    assert set(stub_classes) == set(classes)
    assert stub_functions == functions
    for name, members in classes.items():
        assert stub_classes[name] == members, name


def test_every_public_name_is_documented():
    classes, functions = runtime_tree()
    for name in functions:
        assert getattr(_native, name).__doc__, name
    for cls, members in classes.items():
        obj = getattr(_native, cls)
        assert obj.__doc__, cls
        for m in members:
            doc = getattr(obj, m).__doc__
            assert doc and doc.strip(), f"{cls}.{m}"


def test_the_package_exports_what_the_stubs_and_results_declare():
    for name in flexwing.__all__:
        assert hasattr(flexwing, name), name


def test_the_analysis_names_of_the_stub_are_the_extensions():
    """`AnalysisName` in the stub lists exactly the analyses `Case.run` and `solve_many` take
    (the extension's error for an unknown name lists them)."""
    tree = ast.parse(STUB.read_text())
    literal = next(
        n.value for n in tree.body if isinstance(n, ast.Assign) and getattr(n.targets[0], "id", "") == "AnalysisName"
    )
    stub_names = {e.value for e in literal.slice.elts}
    try:
        flexwing.solve_many([], "no-such-analysis")
    except flexwing.InputError as e:
        names = set(re.findall(r'"([a-z-]+)"', e.reason)) - {"no-such-analysis"}
    assert stub_names == names == {"modes", "static", "dynamic", "flutter", "linearize", "study", "gust", "turbulence"}


def test_every_result_field_is_documented():
    """Every field of every result class (structural and aeroelastic) is named in its class's
    docstring, where its units and shape are given."""
    import dataclasses

    from flexwing import _aero_results, _chain3d_results, _results

    for module in (_results, _aero_results, _chain3d_results):
        for name in module.__all__:
            cls = getattr(module, name)
            if not dataclasses.is_dataclass(cls):
                continue  # Batch: a list, documented in its docstring
            doc = cls.__doc__ or ""
            for f in dataclasses.fields(cls):
                if f.name != "extra":
                    assert re.search(rf"\b{f.name}\b", doc), f"{name}.{f.name} is not documented"
