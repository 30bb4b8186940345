"""Argument conversion shared by the curve and the operations.

Python-side checks exist only where ctypes would otherwise change the value
silently (a negative integer wraps around in ``size_t``) or where the flat C
array cannot express the mistake (ragged point rows). Everything else (NaN,
parameter ranges, orders above the degree...) is left to the library, whose
messages name the argument.
"""

import contextlib
import ctypes
import operator
import re
import struct

from .errors import STATUS_NON_FINITE, BezjoinError


def index_argument(value, name):
    """A non-negative integer for a ``size_t`` argument."""
    try:
        number = operator.index(value)
    except TypeError:
        raise TypeError(f"{name} must be an integer, not {type(value).__name__}") from None
    if isinstance(value, bool):
        raise TypeError(f"{name} must be an integer, not bool")
    if number < 0:
        raise BezjoinError.invalid_argument(f"{name} = {number} is negative")
    if number > SIZE_MAX:
        # ctypes would wrap it around silently (2**64 becomes 0).
        raise BezjoinError.invalid_argument(
            f"{name} = {number} is larger than the largest size_t {SIZE_MAX}")
    return number


#: The largest ``size_t``.
SIZE_MAX = 2 ** (8 * ctypes.sizeof(ctypes.c_size_t)) - 1


def double_buffer(length, name):
    """A zeroed ``double[length]`` for the library to fill, whose size follows from the
    argument ``name``; a size Python cannot allocate is an error naming it."""
    try:
        return (ctypes.c_double * length)()
    except (OverflowError, MemoryError):
        raise BezjoinError.invalid_argument(
            f"{name}: the result would take {length} doubles, more than can be "
            "allocated") from None


def real_argument(value, name):
    """A float for a ``double`` argument (NaN and infinity pass: the library reports them)."""
    if isinstance(value, bool):
        raise TypeError(f"{name} must be a real number, not bool")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a real number, not {type(value).__name__}") from None


BALANCED = "balanced"


def _plain_bool(value):
    """``value`` as a Python bool when it is a bool (also numpy's ``bool_``, what a
    comparison of numpy values gives), else ``None`` (``1``, ``"yes"``, arrays: refused,
    so that a mistyped argument is not read as a flag)."""
    if isinstance(value, bool):
        return value
    kind = type(value)
    if kind.__module__ == "numpy" and kind.__name__ in ("bool_", "bool"):
        return bool(value)
    return None


def automatic_scale(auto_scale, p_scale, q_scale, *, balanced=False):
    """Whether an operation uses the automatic scale, and the explicit scales otherwise.

    The rule of every entry with scales (:func:`bezjoin.connect`, :func:`bezjoin.fillet`,
    :func:`bezjoin.fillet_vertex`, :func:`bezjoin.fillet_chain`): ``auto_scale=None`` (the
    default) means automatic unless ``p_scale`` or ``q_scale`` is given;
    ``auto_scale=True`` is automatic (given scales are ignored, as before);
    ``auto_scale=False`` uses the given scales, a missing one being 1.0 (the
    paper). Where the entry offers it (``balanced=True``), ``auto_scale="balanced"``
    is the automatic scale with both ends of the blend at one speed (given scales
    are ignored). Returns ``(automatic, p_scale, q_scale)`` with the scales as
    floats; ``automatic`` is ``False``, ``True`` or ``"balanced"``.
    """
    if balanced and isinstance(auto_scale, str) and auto_scale == BALANCED:
        pass
    elif auto_scale is not None:
        flag = _plain_bool(auto_scale)
        if flag is None:
            allowed = 'None, a bool or "balanced"' if balanced else "None or a bool"
            raise TypeError(f"auto_scale must be {allowed}, not {auto_scale!r}")
        auto_scale = flag
    if auto_scale is None:
        auto_scale = p_scale is None and q_scale is None
    p_scale = 1.0 if p_scale is None else real_argument(p_scale, "p_scale")
    q_scale = 1.0 if q_scale is None else real_argument(q_scale, "q_scale")
    return auto_scale, p_scale, q_scale


def point_rows(points, name):
    """Rows of floats from a sequence of points (tuples, lists, FreeCAD vectors, numpy rows).

    Returns ``(rows, dim)``. Raises :class:`BezjoinError` (invalid argument)
    for no points, an empty point, or rows of different lengths.
    """
    try:
        # float coordinates pass as they are (real_argument would return them
        # unchanged); the argument name is formatted only for the others.
        rows = [tuple([x if type(x) is float else real_argument(x, f"{name}[{i}] coordinate")
                       for x in row])
                for i, row in enumerate(points)]
    except TypeError as error:
        raise TypeError(f"{name} must be a sequence of points: {error}") from None
    if not rows:
        raise BezjoinError.invalid_argument(f"{name} is empty (a curve needs at least one point)")
    dim = len(rows[0])
    if dim == 0:
        raise BezjoinError.invalid_argument(f"{name}[0] has no coordinates")
    for i, row in enumerate(rows):
        if len(row) != dim:
            raise BezjoinError.invalid_argument(
                f"{name}[{i}] has {len(row)} coordinates but {name}[0] has {dim}"
            )
    return rows, dim


@contextlib.contextmanager
def point_indices(dim, *names):
    """Name a non-finite coordinate by point and coordinate: the library sees the points
    of ``names`` as one flat array and says ``points[7]``; the caller gave rows of
    ``dim`` numbers, so the message says ``points[2][1]`` (user testing, session 40).
    Only the failing call pays for it."""
    try:
        yield
    except BezjoinError as error:
        match = re.match(r"(\w+)\[(\d+)\]", error.message)
        if error.status != STATUS_NON_FINITE or not match or match.group(1) not in names:
            raise
        index = int(match.group(2))
        message = (f"{match.group(1)}[{index // dim}][{index % dim}]"
                   f"{error.message[match.end():]}")
        raise BezjoinError(error.status, error.status_name, message) from None


_ARRAY_TYPES = {}


def _array_type(length):
    """``(ctypes.c_double * length, struct.Struct)``, cached by length."""
    kind = _ARRAY_TYPES.get(length)
    if kind is None:
        if len(_ARRAY_TYPES) > 256:
            _ARRAY_TYPES.clear()
        kind = _ARRAY_TYPES[length] = (ctypes.c_double * length, struct.Struct(f"={length}d"))
    return kind


def double_array(values):
    """A ctypes ``double[]`` holding ``values`` (kept alive by the caller)."""
    values = list(values)
    length = len(values)
    array_type, packer = _array_type(max(length, 1))
    if length:
        try:
            # One copy of packed doubles: much cheaper than ctypes' element-wise init.
            return array_type.from_buffer_copy(packer.pack(*values)), length
        except (struct.error, TypeError, OverflowError, ValueError):
            pass  # let ctypes convert (and word any error) as it always has
    return array_type(*values), length


def flat(rows):
    """Row-major flattening of point rows."""
    return [x for row in rows for x in row]


def rows_of(buffer, count, dim):
    """``count`` rows of ``dim`` floats from a row-major ctypes buffer."""
    values = iter(buffer[:count * dim])  # one slice: plain floats
    # zip of one iterator dim times: the rows as tuples, no per-row slicing.
    return list(zip(*[values] * dim))
