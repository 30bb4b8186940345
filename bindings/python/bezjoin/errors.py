"""The one exception type of the package."""

# Status codes of the C contract (shared/spec/c-api.md); the values are fixed.
STATUS_OK = 0
STATUS_NULL_POINTER = 1
STATUS_INVALID_ARGUMENT = 2
STATUS_NON_FINITE = 3
STATUS_DIMENSION_MISMATCH = 4
STATUS_BUFFER_TOO_SMALL = 5
STATUS_INCONSISTENT = 6
STATUS_SINGULAR = 7
STATUS_ILL_CONDITIONED = 8
STATUS_NO_INTERSECTION = 9
STATUS_INTERNAL = 99

STATUS_NAMES = {
    STATUS_OK: "BZJ_OK",
    STATUS_NULL_POINTER: "BZJ_ERR_NULL_POINTER",
    STATUS_INVALID_ARGUMENT: "BZJ_ERR_INVALID_ARGUMENT",
    STATUS_NON_FINITE: "BZJ_ERR_NON_FINITE",
    STATUS_DIMENSION_MISMATCH: "BZJ_ERR_DIMENSION_MISMATCH",
    STATUS_BUFFER_TOO_SMALL: "BZJ_ERR_BUFFER_TOO_SMALL",
    STATUS_INCONSISTENT: "BZJ_ERR_INCONSISTENT",
    STATUS_SINGULAR: "BZJ_ERR_SINGULAR",
    STATUS_ILL_CONDITIONED: "BZJ_ERR_ILL_CONDITIONED",
    STATUS_NO_INTERSECTION: "BZJ_ERR_NO_INTERSECTION",
    STATUS_INTERNAL: "BZJ_ERR_INTERNAL",
}


class BezjoinError(Exception):
    """A failed bezjoin operation.

    Attributes:
        status: the integer ``BzjStatus`` of the C contract (``2`` for
            ``BZJ_ERR_INVALID_ARGUMENT``, ...).
        status_name: its name as the library spells it (``bzj_status_name``).
        message: the library's message (``bzj_last_error``), which names the
            offending argument, or the Python wrapper's message when the
            argument was rejected before reaching the library (a negative
            order, ragged point rows, a closed curve handle...).
    """

    def __init__(self, status, status_name, message):
        self.status = int(status)
        self.status_name = str(status_name)
        self.message = str(message)
        super().__init__(f"{self.status_name}: {self.message}")

    @classmethod
    def invalid_argument(cls, message):
        """An argument the Python layer rejects, reported as the library would."""
        return cls(STATUS_INVALID_ARGUMENT, STATUS_NAMES[STATUS_INVALID_ARGUMENT], message)

    @classmethod
    def dimension_mismatch(cls, message):
        """Data of the wrong dimension, caught before the library would read past it."""
        return cls(STATUS_DIMENSION_MISMATCH, STATUS_NAMES[STATUS_DIMENSION_MISMATCH], message)


class LibraryNotFoundError(OSError):
    """libbezjoin could not be found or loaded; the message lists every place tried."""


class UnsupportedGeometryError(ValueError):
    """A FreeCAD object that has no exact Bezier or NURBS form (or a curve with no FreeCAD form)."""
