"""Result objects: several curves released together, plus the operation's report."""


class CurveGroup:
    """Curves returned by one operation; ``close()`` (or a ``with`` block) releases them all."""

    _curve_fields = ()

    def curves(self):
        """The curves of this result, in field order (missing ones skipped)."""
        return [c for c in (getattr(self, name) for name in self._curve_fields) if c is not None]

    def close(self):
        """Release every curve of the result (idempotent)."""
        for curve in self.curves():
            curve.close()

    def __enter__(self):
        return self

    def __exit__(self, *exception):
        self.close()
        return False

    def __repr__(self):
        fields = ", ".join(f"{name}={getattr(self, name)!r}" for name in self._fields())
        return f"{type(self).__name__}({fields})"

    def _fields(self):
        return self._curve_fields
