"""The type stubs and docstrings: every public name of the compiled module has a stub, and
every function, class and method a docstring, so that editors complete and explain them."""

import ast
import inspect
import pathlib

import adb
from adb import _adb


def stub_names():
    tree = ast.parse(pathlib.Path(_adb.__file__).with_name("_adb.pyi").read_text())
    names = {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            members = {n.name for n in getattr(node, "body", [])
                       if isinstance(n, ast.FunctionDef)}
            members |= {n.target.id for n in getattr(node, "body", [])
                        if isinstance(n, ast.AnnAssign)}
            names[node.name] = members
    return names


def public(obj):
    return [n for n in dir(obj) if not n.startswith("_")]


def test_every_public_name_has_a_stub():
    stubs = stub_names()
    for name in public(_adb):
        assert name in stubs, f"adb._adb.{name} has no stub"
        obj = getattr(_adb, name)
        if inspect.isclass(obj) and not issubclass(obj, Exception):
            for member in public(obj):
                assert member in stubs[name], f"adb.{name}.{member} has no stub"


def test_every_public_name_has_a_docstring():
    for name in public(_adb):
        obj = getattr(_adb, name)
        assert (obj.__doc__ or "").strip(), f"adb.{name} has no docstring"
        if inspect.isclass(obj) and not issubclass(obj, Exception):
            for member in public(obj):
                doc = getattr(obj, member).__doc__ or ""
                assert doc.strip(), f"adb.{name}.{member} has no docstring"
    for name in ("CollisionManager", "Contact"):
        assert getattr(adb, name).__doc__
        for member in public(getattr(adb, name)):
            if callable(getattr(getattr(adb, name), member)):
                assert getattr(getattr(adb, name), member).__doc__, f"{name}.{member}"
