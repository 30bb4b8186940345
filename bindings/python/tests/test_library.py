"""Finding and loading the library, status names, version."""

import os
import re
import shutil
import subprocess
import sys

import pytest

import bezjoin
from bezjoin import _library
from bezjoin.errors import STATUS_NAMES, LibraryNotFoundError

PYTHON_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PACKAGE = os.path.join(PYTHON_ROOT, "bezjoin")
REPOSITORY = os.path.dirname(os.path.dirname(PYTHON_ROOT))


def test_lookup_order_without_environment_variable():
    paths = [path for _origin, path in _library.candidate_paths({}, PACKAGE, "libx.so")]
    assert paths == [
        os.path.join(PACKAGE, "libx.so"),
        os.path.join(PYTHON_ROOT, "libx.so"),
        os.path.join(REPOSITORY, "target", "release", "libx.so"),
    ]


def test_environment_variable_is_the_only_candidate_when_set():
    environ = {"BEZJOIN_LIBRARY": "/somewhere/libbezjoin.so"}
    assert _library.candidate_paths(environ, PACKAGE) == [
        ("BEZJOIN_LIBRARY", "/somewhere/libbezjoin.so")]
    with pytest.raises(LibraryNotFoundError, match="/somewhere/libbezjoin.so"):
        _library.find_library(environ, PACKAGE)


def test_empty_environment_variable_is_ignored():
    assert len(_library.candidate_paths({"BEZJOIN_LIBRARY": ""}, PACKAGE)) == 3


def test_first_existing_candidate_wins(tmp_path):
    package = tmp_path / "repo" / "bindings" / "python" / "bezjoin"
    release = tmp_path / "repo" / "target" / "release"
    package.mkdir(parents=True)
    release.mkdir(parents=True)
    (release / "libx.so").write_bytes(b"")
    assert _library.find_library({}, str(package), "libx.so") == str(release / "libx.so")
    (package.parent / "libx.so").write_bytes(b"")
    assert _library.find_library({}, str(package), "libx.so") == str(package.parent / "libx.so")
    (package / "libx.so").write_bytes(b"")
    assert _library.find_library({}, str(package), "libx.so") == str(package / "libx.so")


def test_not_found_names_every_path_tried(tmp_path):
    package = tmp_path / "bezjoin"
    with pytest.raises(LibraryNotFoundError) as caught:
        _library.find_library({}, str(package), "libx.so")
    for _origin, path in _library.candidate_paths({}, str(package), "libx.so"):
        assert path in str(caught.value)


def test_file_names_per_platform():
    assert _library.library_file_name("linux") == "libbezjoin.so"
    assert _library.library_file_name("darwin") == "libbezjoin.dylib"
    assert _library.library_file_name("win32") == "bezjoin.dll"


def test_loading_something_that_is_not_a_library(tmp_path):
    fake = tmp_path / "libbezjoin.so"
    fake.write_text("not an ELF file")
    with pytest.raises(LibraryNotFoundError, match="cannot load"):
        _library.Library(str(fake))


def test_loading_a_library_that_is_not_bezjoin():
    import ctypes.util

    other = ctypes.util.find_library("m")
    if other is None:
        pytest.skip("no libm to load")
    with pytest.raises(LibraryNotFoundError, match="is not libbezjoin"):
        _library.Library(other)


def _run_with_environment(environment_value):
    environ = dict(os.environ, BEZJOIN_LIBRARY=environment_value, PYTHONPATH=PYTHON_ROOT)
    code = "import bezjoin; print(bezjoin.library_path()); print(bezjoin.Curve([(1.0,)]).dim)"
    return subprocess.run([sys.executable, "-c", code], env=environ, capture_output=True,
                          text=True, check=False)


def test_environment_variable_selects_the_library(tmp_path):
    copy = tmp_path / "copy-of-libbezjoin.so"
    shutil.copy(bezjoin.library_path(), copy)
    result = _run_with_environment(str(copy))
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == [str(copy), "1"]


def test_wrong_environment_variable_is_an_error_not_a_fallback(tmp_path):
    result = _run_with_environment(str(tmp_path / "missing.so"))
    assert result.returncode != 0
    assert "LibraryNotFoundError" in result.stderr
    assert "missing.so" in result.stderr


def test_importing_never_needs_the_library(tmp_path):
    environ = dict(os.environ, BEZJOIN_LIBRARY=str(tmp_path / "missing.so"),
                   PYTHONPATH=PYTHON_ROOT)
    result = subprocess.run([sys.executable, "-c", "import bezjoin; print('imported')"],
                            env=environ, capture_output=True, text=True, check=False)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "imported"


def test_version_is_semantic():
    assert re.fullmatch(r"0\.\d+\.\d+", bezjoin.library_version())


def test_status_names_agree_with_the_library():
    for status, name in STATUS_NAMES.items():
        assert bezjoin.status_name(status) == name
    assert bezjoin.status_name(12345) == "BZJ_UNKNOWN_STATUS"


def test_library_reports_missing_function():
    library = _library.library()
    with pytest.raises(LibraryNotFoundError, match="has no bzj_no_such_function"):
        library.function("bzj_no_such_function")


OPERATION_SYMBOLS = {
    "connect": "bzj_connect",
    "fillet": "bzj_fillet",
    "intersect": "bzj_intersect",
    "merge": "bzj_merge",
    "lagrange_spline": "bzj_lagrange_spline",
}


def test_every_exposed_operation_exists_in_the_library():
    # The five operations of issue 9, named explicitly: each is exposed,
    # exported, callable, and backed by its C function in the loaded library.
    assert sorted(OPERATION_SYMBOLS) == ["connect", "fillet", "intersect", "lagrange_spline",
                                         "merge"]
    library = _library.library()
    for name, symbol in OPERATION_SYMBOLS.items():
        assert callable(getattr(bezjoin, name, None)), f"bezjoin.{name} is not exposed"
        assert name in bezjoin.__all__, name
        assert library.has(symbol), symbol
    assert not library.has("bzj_no_such_function")
