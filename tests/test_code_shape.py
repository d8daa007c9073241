"""The package's code shape (issue 58): no function longer than ``MAX_FUNCTION_LINES`` and no
class docstring longer than ``MAX_CLASS_DOCSTRING_LINES``, read from every module under
``gripper/`` with :mod:`ast`. Each failure lists every offender, with its file, line and length."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "gripper"
MAX_FUNCTION_LINES = 80  # def line to last line, inclusive (decorators not counted)
MAX_CLASS_DOCSTRING_LINES = 40  # first to last line of the docstring, inclusive


def _trees():
    for path in sorted(PACKAGE.rglob("*.py")):
        yield path.relative_to(ROOT), ast.parse(path.read_text(), filename=str(path))


def _qualified(tree: ast.Module):
    """Every function, method and class of ``tree`` with its dotted name (``Class.method``,
    ``outer.<locals>.inner``)."""
    stack = [(node, "") for node in tree.body]
    while stack:
        node, prefix = stack.pop()
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            name = f"{prefix}{node.name}"
            yield node, name
            inner = f"{name}.<locals>." if not isinstance(node, ast.ClassDef) else f"{name}."
            stack.extend((child, inner) for child in ast.iter_child_nodes(node))
        else:
            stack.extend((child, prefix) for child in ast.iter_child_nodes(node))


def _span(node: ast.AST) -> int:
    assert node.end_lineno is not None
    return node.end_lineno - node.lineno + 1


def test_no_function_is_longer_than_the_limit():
    long = sorted(f"{path}:{node.lineno} {name} ({_span(node)} lines)"
                  for path, tree in _trees() for node, name in _qualified(tree)
                  if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)
                  and _span(node) > MAX_FUNCTION_LINES)
    assert not long, (f"{len(long)} function(s) longer than {MAX_FUNCTION_LINES} lines (def line "
                      f"to last line); split them into helpers:\n  " + "\n  ".join(long))


def test_no_class_docstring_is_longer_than_the_limit():
    long = []
    for path, tree in _trees():
        for node, name in _qualified(tree):
            if not isinstance(node, ast.ClassDef) or ast.get_docstring(node) is None:
                continue
            doc = node.body[0]
            if _span(doc) > MAX_CLASS_DOCSTRING_LINES:
                long.append(f"{path}:{doc.lineno} {name} ({_span(doc)} lines)")
    long.sort()
    assert not long, (f"{len(long)} class docstring(s) longer than {MAX_CLASS_DOCSTRING_LINES} "
                      f"lines; move the detail to the module docstring or the docs:\n  "
                      + "\n  ".join(long))
