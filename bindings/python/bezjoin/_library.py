"""Finding, loading and calling libbezjoin through ctypes.

The library is looked up, in this order:

1. the file named by the environment variable ``BEZJOIN_LIBRARY`` (when it is
   set, nothing else is tried: a wrong value is an error, not a silent
   fallback to another copy);
2. next to the package: inside the ``bezjoin`` package folder, then in the
   folder that holds it;
3. ``target/release/`` of the repository the package sits in
   (``<repo>/bindings/python/bezjoin`` -> ``<repo>/target/release``), where
   ``cargo build --release -p bezjoin-ffi`` puts it.

Loading is lazy (on the first call that needs the library), so importing the
package never fails for lack of the shared library.
"""

import ctypes
import os
import sys
import threading

from .errors import STATUS_NAMES, STATUS_OK, BezjoinError, LibraryNotFoundError

ENVIRONMENT_VARIABLE = "BEZJOIN_LIBRARY"

#: The ABI major version these bindings are written against (``BZJ_VERSION_MAJOR``).
SUPPORTED_MAJOR_VERSION = 0


def library_file_name(platform=None):
    """The file name of the shared library on ``platform`` (default: this one)."""
    platform = sys.platform if platform is None else platform
    if platform.startswith("win"):
        return "bezjoin.dll"
    if platform == "darwin":
        return "libbezjoin.dylib"
    return "libbezjoin.so"


def candidate_paths(environ=None, package_directory=None, file_name=None):
    """Where the library is looked for, in order, as ``(origin, path)`` pairs.

    With ``BEZJOIN_LIBRARY`` set (and non-empty) it is the only candidate.
    """
    environ = os.environ if environ is None else environ
    if package_directory is None:
        package_directory = os.path.dirname(os.path.abspath(__file__))
    file_name = library_file_name() if file_name is None else file_name
    explicit = environ.get(ENVIRONMENT_VARIABLE, "")
    if explicit:
        return [(ENVIRONMENT_VARIABLE, explicit)]
    parent = os.path.dirname(package_directory)
    repository = os.path.dirname(os.path.dirname(parent))
    return [
        ("package folder", os.path.join(package_directory, file_name)),
        ("next to the package", os.path.join(parent, file_name)),
        ("repository build", os.path.join(repository, "target", "release", file_name)),
    ]


def find_library(environ=None, package_directory=None, file_name=None):
    """The path of the library that would be loaded.

    Raises:
        LibraryNotFoundError: naming every path tried.
    """
    candidates = candidate_paths(environ, package_directory, file_name)
    for _origin, path in candidates:
        if os.path.isfile(path):
            return path
    tried = "; ".join(f"{origin}: {path}" for origin, path in candidates)
    raise LibraryNotFoundError(
        f"libbezjoin not found (tried {tried}). Build it with "
        f"`cargo build --release -p bezjoin-ffi` or set {ENVIRONMENT_VARIABLE} "
        f"to the library file."
    )


class CurveHandle(ctypes.Structure):
    """The opaque ``BzjCurve`` (never dereferenced on the Python side)."""


CurvePointer = ctypes.POINTER(CurveHandle)

_size = ctypes.c_size_t
_double = ctypes.c_double
_status = ctypes.c_int32
_double_pointer = ctypes.POINTER(ctypes.c_double)
_size_pointer = ctypes.POINTER(ctypes.c_size_t)
_curve_out = ctypes.POINTER(CurvePointer)

# name -> (restype, argtypes). Functions of the C contract only.
_PROTOTYPES = {
    "bzj_version": (ctypes.c_char_p, []),
    "bzj_last_error": (ctypes.c_char_p, []),
    "bzj_status_name": (ctypes.c_char_p, [ctypes.c_int32]),
    "bzj_curve_new": (_status, [_size, _size, _double_pointer, _size, _curve_out]),
    "bzj_curve_free": (None, [CurvePointer]),
    "bzj_curve_degree": (_status, [CurvePointer, _size_pointer]),
    "bzj_curve_dim": (_status, [CurvePointer, _size_pointer]),
    "bzj_curve_points": (_status, [CurvePointer, _double_pointer, _size]),
    "bzj_curve_eval": (_status, [CurvePointer, _double, _size, _double_pointer, _size]),
    "bzj_curve_eval_many": (
        _status,
        [CurvePointer, _double_pointer, _size, _size, _double_pointer, _size],
    ),
    "bzj_curve_elevate": (_status, [CurvePointer, _size, _curve_out]),
    "bzj_curve_split": (_status, [CurvePointer, _double, _curve_out, _curve_out]),
    "bzj_curve_segment": (_status, [CurvePointer, _double, _double, _curve_out]),
    "bzj_curve_reverse": (_status, [CurvePointer, _curve_out]),
    "bzj_curve_length": (_status, [CurvePointer, _double, _double, _double_pointer]),
}

_REQUIRED = tuple(_PROTOTYPES)


def register_prototype(name, restype, argtypes):
    """Declare the signature of an operation module's C function (at import)."""
    _PROTOTYPES[name] = (restype, list(argtypes))


class Library:
    """A loaded libbezjoin with its function prototypes declared."""

    def __init__(self, path):
        self.path = path
        try:
            self._cdll = ctypes.CDLL(path)
        except OSError as error:
            raise LibraryNotFoundError(f"cannot load libbezjoin from {path}: {error}") from error
        missing = [name for name in _REQUIRED if not hasattr(self._cdll, name)]
        if missing:
            raise LibraryNotFoundError(
                f"{path} is not libbezjoin: it lacks {', '.join(missing)}"
            )
        self._functions = {}
        self.version = self.function("bzj_version")().decode("utf-8")
        major = int(self.version.split(".")[0])
        if major != SUPPORTED_MAJOR_VERSION:
            raise LibraryNotFoundError(
                f"{path} is libbezjoin {self.version}; these bindings need "
                f"major version {SUPPORTED_MAJOR_VERSION}"
            )

    def has(self, name):
        """Whether the loaded library exports ``name``."""
        return hasattr(self._cdll, name)

    def function(self, name):
        """The C function ``name`` with its prototype declared."""
        function = self._functions.get(name)
        if function is None:
            if not self.has(name):
                raise LibraryNotFoundError(
                    f"the library at {self.path} (version {self.version}) has no {name}; "
                    "rebuild it from the same source as these bindings"
                )
            function = getattr(self._cdll, name)
            restype, argtypes = _PROTOTYPES[name]
            function.restype = restype
            function.argtypes = argtypes
            self._functions[name] = function
        return function

    def status_name(self, status):
        """``bzj_status_name(status)``."""
        return self.function("bzj_status_name")(int(status)).decode("utf-8")

    def last_error(self):
        """``bzj_last_error()`` of the calling thread."""
        return self.function("bzj_last_error")().decode("utf-8", errors="replace")

    def call(self, name, *arguments):
        """Call a status-returning function; raise :class:`BezjoinError` unless ``BZJ_OK``.

        The message is read in the same thread right after the call, as the
        contract requires (``bzj_last_error`` is per thread).
        """
        status = self.function(name)(*arguments)
        if status != STATUS_OK:
            raise BezjoinError(status, self.status_name(status), self.last_error())


_lock = threading.Lock()
_library = None


def library():
    """The process-wide loaded library (loaded on first use)."""
    global _library
    if _library is None:
        with _lock:
            if _library is None:
                _library = Library(find_library())
    return _library


_cached_functions = {}


def function(name):
    """``library().function(name)``, kept per loaded library: the hot paths' lookup
    (one dictionary read instead of two and a method call)."""
    cached = _cached_functions.get(name)
    if cached is None or cached[0] is not _library:
        lib = library()
        cached = _cached_functions[name] = (lib, lib.function(name))
    return cached[1]


def status_name(status):
    """The library's name for a status value (``bzj_status_name``)."""
    return library().status_name(status)


def library_version():
    """The loaded library's version string, ``"MAJOR.MINOR.PATCH"``."""
    return library().version


def library_path():
    """The path of the loaded library file."""
    return library().path


__all__ = [
    "ENVIRONMENT_VARIABLE",
    "STATUS_NAMES",
    "candidate_paths",
    "find_library",
    "library",
    "library_file_name",
    "library_path",
    "library_version",
    "status_name",
]
