"""The type stubs of the native module name what it holds."""

import ast
import inspect

import lagrangian
from conftest import ROOT


def stubbed():
    tree = ast.parse((ROOT / "python" / "lagrangian" / "_lagrangian.pyi").read_text())
    functions = {node.name for node in tree.body if isinstance(node, ast.FunctionDef)}
    classes = {node.name: {item.name for item in node.body if isinstance(item, ast.FunctionDef)}
               for node in tree.body if isinstance(node, ast.ClassDef)}
    return functions, classes


def test_every_function_and_class_of_the_native_module_has_its_stub():
    native = lagrangian._lagrangian
    functions, classes = stubbed()
    public = {name for name in dir(native) if not name.startswith("_")}
    assert public == functions | set(classes)
    for name, methods in classes.items():
        members = {m for m, _ in inspect.getmembers(getattr(native, name)) if not m.startswith("_")}
        assert members == methods - {"__init__"}, name
