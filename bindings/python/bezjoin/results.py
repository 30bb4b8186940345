"""Result objects: several curves released together, plus the operation's report."""


class CurveGroup:
    """Curves returned by one operation; ``close()`` (or a ``with`` block) releases them all."""

    _curve_fields = ()

    def curves(self):
        """The curves of this result, in field order (missing ones skipped; a field
        holding a list of curves contributes them all, in order)."""
        out = []
        for name in self._curve_fields:
            value = getattr(self, name)
            if isinstance(value, list):
                out.extend(c for c in value if c is not None)
            elif value is not None:
                out.append(value)
        return out

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
