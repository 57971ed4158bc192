# SPDX-License-Identifier: Apache-2.0
"""The package is typed: it ships its stubs and the py.typed marker, mypy --strict accepts the
package and the examples, and everything public has a docstring for help()."""
import inspect
import pathlib

import pytest

import libppm

PACKAGE = pathlib.Path(libppm.__file__).parent
EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"


def test_stubs_and_marker_are_installed():
    assert (PACKAGE / "py.typed").is_file()
    stub = (PACKAGE / "_core.pyi").read_text()
    # The generated stub describes the extension's classes and their signatures.
    assert "class Renderer:" in stub
    assert "def ray_layout() -> dict[str, Any]" in stub


def run_mypy(tmp_path, *targets):
    api = pytest.importorskip("mypy.api")
    stdout, stderr, status = api.run(["--strict", "--cache-dir", str(tmp_path / "cache"),
                                      "--no-error-summary", *targets])
    assert status == 0, stdout + stderr


def test_mypy_strict_accepts_the_package(tmp_path):
    run_mypy(tmp_path, "-p", "libppm")


def test_mypy_strict_accepts_the_examples(tmp_path):
    examples = sorted(str(p) for p in EXAMPLES.glob("*.py"))
    assert examples
    run_mypy(tmp_path, *examples)


def test_mypy_strict_rejects_a_wrongly_typed_call(tmp_path):
    """The annotations are not Any everywhere: a bad argument type is caught."""
    program = tmp_path / "wrong.py"
    program.write_text("import libppm\n"
                       "image = libppm.render('scene.json', passes='many')\n")
    api = pytest.importorskip("mypy.api")
    stdout, _, status = api.run(["--strict", "--cache-dir", str(tmp_path / "cache"),
                                 str(program)])
    assert status == 1
    assert "passes" in stdout and "arg-type" in stdout


def public_members():
    for name in libppm.__all__:
        value = getattr(libppm, name)
        if inspect.isclass(value) or inspect.isfunction(value):
            yield name, value
            if inspect.isclass(value) and not issubclass(value, BaseException):
                for member, attribute in vars(value).items():
                    if not member.startswith("_") and (inspect.isfunction(attribute)
                                                       or isinstance(attribute, property)):
                        yield f"{name}.{member}", attribute


def test_everything_public_has_a_docstring():
    missing = [name for name, value in public_members() if not inspect.getdoc(value)]
    assert not missing, f"no docstring: {missing}"
