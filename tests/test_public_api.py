"""The public names are exported, documented and importable."""

import importlib
import inspect

import pytest

import kb


def test_kb_exports():
    assert sorted(kb.__all__) == sorted(set(kb.__all__))
    for name in kb.__all__:
        assert hasattr(kb, name), name


@pytest.mark.parametrize("module", ["kb.features", "kb.errors", "kb.catalog", "kb.csvio"])
def test_module_all_is_complete_and_documented(module):
    mod = importlib.import_module(module)
    assert mod.__doc__ and mod.__all__
    for name in mod.__all__:
        obj = getattr(mod, name)
        if inspect.isfunction(obj) or inspect.isclass(obj):
            assert obj.__doc__, f"{module}.{name} has no docstring"


def test_error_tree_in_docstring_names_every_error():
    from kb import errors

    for name in errors.__all__:
        assert name in errors.__doc__, name
        assert issubclass(getattr(errors, name), errors.ObjrecallError)
