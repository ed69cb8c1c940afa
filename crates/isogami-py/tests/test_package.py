"""The package itself: every public name documented, typed in the stubs and exercised by a
test; help() useful; the installed package carries its stubs and py.typed marker."""

import ast
import doctest
import inspect
import pydoc
import re
from pathlib import Path

import isogami

HERE = Path(__file__).resolve().parent
PACKAGE = Path(isogami.__file__).resolve().parent


def public():
    return [n for n in isogami.__all__ if not n.startswith("_")]


def test_all_matches_the_native_module():
    native = isogami._isogami
    exported = {n for n in dir(native) if not n.startswith("_")}
    assert exported == set(public())
    for name in public():
        assert getattr(isogami, name) is getattr(native, name)
    assert re.fullmatch(r"\d+\.\d+\.\d+", isogami.__version__)


def test_every_public_name_has_a_docstring():
    missing = []
    for name in public():
        obj = getattr(isogami, name)
        if isinstance(obj, (list, str)):
            continue
        if not (obj.__doc__ or "").strip():
            missing.append(name)
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            for attr, member in vars(obj).items():
                if attr.startswith("_"):
                    continue
                if not (getattr(member, "__doc__", None) or "").strip():
                    missing.append(f"{name}.{attr}")
    assert missing == []


def test_help_of_deploy_is_useful():
    text = pydoc.render_doc(isogami.deploy, renderer=pydoc.plaintext)
    for needle in ["deploy(design, settings=None, *, frames=None, progress=None, timeout=None, **overrides)",
                   "DeploySettings", "progress", "timeout", "CancelledError", "GIL", "Ctrl-C",
                   "SettingsError", "\"all\""]:
        assert needle in text, needle
    assert "kerf" in pydoc.render_doc(isogami.DeploySettings, renderer=pydoc.plaintext)


def test_stubs_type_every_public_name():
    stub = PACKAGE / "_isogami.pyi"
    assert stub.is_file() and (PACKAGE / "py.typed").is_file()
    tree = ast.parse(stub.read_text())
    defined = set()
    members = {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            defined.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            defined.add(node.target.id)
        elif isinstance(node, ast.Assign):
            defined.update(t.id for t in node.targets if isinstance(t, ast.Name))
        if isinstance(node, ast.ClassDef):
            members[node.name] = {
                n.name if isinstance(n, ast.FunctionDef) else n.target.id
                for n in node.body
                if isinstance(n, ast.FunctionDef) or (isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name))
            }
    assert set(public()) - defined == set()
    # Every public method and property of every class is in its stub.
    for name, names in members.items():
        cls = getattr(isogami, name)
        if issubclass(cls, BaseException):
            continue
        real = {a for a in vars(cls) if not a.startswith("_")}
        assert real - names == set(), f"{name}: not in the stub: {sorted(real - names)}"


def test_every_public_name_is_tested():
    sources = "\n".join(p.read_text() for p in HERE.glob("test_*.py") if p.name != Path(__file__).name)
    untested = [n for n in public() if not re.search(rf"\bisogami\.{re.escape(n)}\b", sources)]
    assert untested == []


def test_docstring_examples_run():
    finder, runner = doctest.DocTestFinder(recurse=False), doctest.DocTestRunner()
    examples = 0
    for obj, name in [(isogami, "isogami"), (isogami.deploy, "isogami.deploy")]:
        for test in finder.find(obj, name, globs={"isogami": isogami}):
            examples += len(test.examples)
            runner.run(test)
    assert examples >= 5 and runner.summarize(verbose=False).failed == 0
