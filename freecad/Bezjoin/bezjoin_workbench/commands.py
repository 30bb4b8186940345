"""Thin GUI commands over :mod:`bezjoin_workbench.operations`.

Each command reads the selection, asks for its parameters in a small form,
calls the plain operation, and adds a ``Part::Feature`` with the result. Errors
(unsupported geometry, the library's status and message) are shown in a
message box and the report view; nothing is created then.
"""

import FreeCAD
import FreeCADGui
from PySide import QtGui

from . import operations
from .operations import bezjoin


class SelectionError(Exception):
    """The selection does not fit the command."""


def selected_edges(count):
    """Exactly ``count`` edges from the selection, in the order they were picked
    (sub-elements, or objects whose shape is a single edge)."""
    edges = []
    for selection in FreeCADGui.Selection.getSelectionEx():
        if selection.SubObjects:
            edges.extend(s for s in selection.SubObjects if s.ShapeType == "Edge")
        elif hasattr(selection.Object, "Shape") and len(selection.Object.Shape.Edges) == 1:
            edges.append(selection.Object.Shape.Edges[0])
    if len(edges) != count:
        raise SelectionError(f"select exactly {count} edges (found {len(edges)})")
    return edges


def selected_path():
    """The edges of one selected wire (in its order), or picked edges in the order
    they were picked (at least two)."""
    selections = FreeCADGui.Selection.getSelectionEx()
    edges = [s for sel in selections for s in sel.SubObjects if s.ShapeType == "Edge"]
    if not edges and len(selections) == 1 and hasattr(selections[0].Object, "Shape"):
        wires = selections[0].Object.Shape.Wires
        if len(wires) == 1:
            edges = list(wires[0].OrderedEdges)
    if len(edges) < 2:
        raise SelectionError("select one wire (a sketch, a polyline...) or its edges in path "
                             f"order (found {len(edges)} edges)")
    return edges


def selected_points():
    """On-curve points: picked vertices in order, or the ordered vertices of one
    selected wire (a polyline through the points)."""
    selections = FreeCADGui.Selection.getSelectionEx()
    vertices = [s for sel in selections for s in sel.SubObjects if s.ShapeType == "Vertex"]
    if vertices:
        return [v.Point for v in vertices]
    if len(selections) == 1 and hasattr(selections[0].Object, "Shape"):
        wires = selections[0].Object.Shape.Wires
        if len(wires) == 1:
            return [v.Point for v in wires[0].OrderedVertexes]
    raise SelectionError("select the on-curve points as vertices (in order) or one polyline")


def ask(title, fields):
    """A modal form; ``fields`` are ``(key, label, kind, default, extra)`` with kind
    ``"int"`` (extra: minimum; -1 shows "curve degree"), ``"float"`` (extra:
    (minimum, maximum)), ``"bool"`` or ``"choice"`` (extra: the choices).
    Returns the values by key, or None when cancelled."""
    dialog = QtGui.QDialog(FreeCADGui.getMainWindow())
    dialog.setWindowTitle(title)
    layout = QtGui.QFormLayout(dialog)
    readers = {}
    for key, label, kind, default, extra in fields:
        if kind == "int":
            widget = QtGui.QSpinBox()
            widget.setRange(extra, 25)
            if extra < 0:
                widget.setSpecialValueText("curve degree")
            widget.setValue(default)
            readers[key] = (lambda w: (lambda: None if w.value() < 0 else w.value()))(widget)
        elif kind == "float":
            widget = QtGui.QDoubleSpinBox()
            widget.setDecimals(6)
            widget.setRange(*extra)
            widget.setValue(default)
            readers[key] = widget.value
        elif kind == "bool":
            widget = QtGui.QCheckBox()
            widget.setChecked(default)
            readers[key] = widget.isChecked
        else:
            widget = QtGui.QComboBox()
            widget.addItems(list(extra))
            widget.setCurrentIndex(list(extra).index(default))
            readers[key] = widget.currentText
        layout.addRow(label, widget)
    buttons = QtGui.QDialogButtonBox(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)
    buttons.accepted.connect(dialog.accept)
    buttons.rejected.connect(dialog.reject)
    layout.addRow(buttons)
    if not dialog.exec_():
        return None
    return {key: read() for key, read in readers.items()}


ORDER_FIELDS = [
    ("p_order", "Continuity order at the first edge", "int", -1, -1),
    ("q_order", "Continuity order at the second edge", "int", -1, -1),
    ("p_scale", "Shape scale at the first edge (when not automatic)", "float", 1.0,
     (1e-6, 1e6)),
    ("q_scale", "Shape scale at the second edge (when not automatic)", "float", 1.0,
     (1e-6, 1e6)),
]

#: Checked by default: the automatic scale never loops (the paper's scale 1 can,
#: when the edges are long against the gap or the setback); unchecked, the two
#: scales above are used.
AUTO_SCALE_FIELD = ("auto_scale", "Choose the scales automatically (least bending; never loops)",
                    "bool", True, None)


class Command:
    """Common frame: selection, form, operation, feature, error display."""

    title = ""
    tooltip = ""
    fields = []

    def GetResources(self):  # noqa: N802 (FreeCAD's name)
        return {"MenuText": self.title, "ToolTip": self.tooltip}

    def IsActive(self):  # noqa: N802 (FreeCAD's name)
        return FreeCAD.ActiveDocument is not None

    def Activated(self):  # noqa: N802 (FreeCAD's name)
        document = FreeCAD.ActiveDocument
        try:
            inputs = self.inputs()
            parameters = ask(self.title, self.fields) if self.fields else {}
            if parameters is None:
                return
            document.openTransaction(self.title)
            try:
                self.run(document, inputs, parameters)
            finally:
                document.commitTransaction()
            document.recompute()
        except (SelectionError, bezjoin.BezjoinError, bezjoin.UnsupportedGeometryError,
                bezjoin.LibraryNotFoundError) as error:
            FreeCAD.Console.PrintError(f"{self.title}: {error}\n")
            QtGui.QMessageBox.warning(FreeCADGui.getMainWindow(), self.title, str(error))

    def inputs(self):
        """Two selected edges (the spline command overrides this)."""
        return selected_edges(2)


class BlendCommand(Command):
    title = "Blend two edges"
    tooltip = ("Connect two Bezier edges with a Bezier curve of prescribed continuity "
               "(bezjoin connect)")
    fields = [
        ("u0", "Position on the first edge (fraction of its range; 1 = its end)", "float", 1.0,
         (0.0, 1.0)),
        ("v0", "Position on the second edge (fraction of its range; 0 = its start)", "float",
         0.0, (0.0, 1.0)),
    ] + ORDER_FIELDS + [AUTO_SCALE_FIELD]

    def run(self, document, inputs, parameters):
        shape = operations.blend_edges(inputs[0], inputs[1], **parameters)
        operations.add_feature(document, "Blend", shape)


class RoundCornerCommand(Command):
    title = "Round corner"
    tooltip = "Round the corner between two Bezier edges (bezjoin fillet)"
    fields = [
        ("setback", "Setback along the first edge", "float", 1.0, (1e-9, 1e9)),
        ("second_setback", "Setback along the second edge", "float", 1.0, (1e-9, 1e9)),
    ] + ORDER_FIELDS + [
        AUTO_SCALE_FIELD,
        ("reverse_first", "Reverse the first edge (crossing edges)", "bool", False, None),
        ("reverse_second", "Reverse the second edge (crossing edges)", "bool", False, None),
    ]

    def run(self, document, inputs, parameters):
        shape = operations.round_corner(inputs[0], inputs[1], **parameters)
        operations.add_feature(document, "RoundedCorner", shape)


class RoundWireByRadiusCommand(Command):
    title = "Round wire corners by radius"
    tooltip = ("Round every corner of a wire (open or closed) like the circular fillet of a "
               "radius, with a fair G2 (or G^k) blend at each (bezjoin fillet_radius_chain)")
    fields = [
        ("radius", "Radius", "float", 1.0, (1e-9, 1e9)),
        ("order", "Geometric continuity order G^k (1..6)", "int", 2, 1),
        ("closed", "Closed: also round the corner from the last edge to the first "
                   "(\"auto\": when the wire closes)", "choice", "auto", ("auto", "yes", "no")),
    ]

    def inputs(self):
        return selected_path()

    def run(self, document, inputs, parameters):
        closed = {"auto": None, "yes": True, "no": False}[parameters.pop("closed")]
        rounded = operations.round_wire_by_radius(inputs, closed=closed, **parameters)
        operations.add_feature(document, "RoundedWire", rounded.shape, {
            "FilletRadius": parameters["radius"],
            "MaxArcDeviation": rounded.max_arc_deviation})
        FreeCAD.Console.PrintMessage(f"{self.title}: {rounded.describe()}\n")


class MergeCommand(Command):
    title = "Merge two edges"
    tooltip = "Replace two consecutive Bezier edges by one Bezier edge (bezjoin merge)"
    fields = [
        ("metric", "Metric", "choice", "discrete", ("discrete", "l2")),
        ("mu_mode", "Split parameter mu", "choice", "half", ("half", "polygon", "optimal",
                                                             "given")),
        ("mu", "mu (when given)", "float", 0.5, (1e-6, 1 - 1e-6)),
        ("fix_ends", "Keep the outer end points", "bool", False, None),
        ("keep_first", "Keep the first edge unchanged", "bool", False, None),
        ("keep_second", "Keep the second edge unchanged", "bool", False, None),
    ]

    def run(self, document, inputs, parameters):
        mode, mu = parameters.pop("mu_mode"), parameters.pop("mu")
        merged = operations.merge_edges(inputs[0], inputs[1], mu=mu if mode == "given" else mode,
                                        **parameters)
        operations.add_feature(document, "Merged", merged.shape, {
            "MergeMu": merged.mu, "MergeMetric": merged.metric_value,
            "MergeMaxDeviation": merged.max_deviation})
        FreeCAD.Console.PrintMessage(f"{self.title}: {merged.describe()}\n")


class SplineCommand(Command):
    title = "Spline through on-curve points"
    tooltip = ("C1 cubic spline whose Bezier segments pass through the selected points: "
               "node, two inner points, node, then inner point and node per segment")
    fields = []

    def inputs(self):
        return selected_points()

    def run(self, document, inputs, parameters):
        shape = operations.spline_through_points(inputs)
        operations.add_feature(document, "OnCurveSpline", shape)


#: Command name -> command, for the operations the loaded bindings provide.
COMMANDS = {
    "Bezjoin_Blend": (BlendCommand, "connect"),
    "Bezjoin_RoundCorner": (RoundCornerCommand, "fillet"),
    "Bezjoin_RoundWireByRadius": (RoundWireByRadiusCommand, "fillet_radius_chain"),
    "Bezjoin_Merge": (MergeCommand, "merge"),
    "Bezjoin_Spline": (SplineCommand, "lagrange_spline"),
}


def register():
    """Register the commands whose operation exists; return their names."""
    names = []
    for name, (command, operation) in COMMANDS.items():
        if hasattr(bezjoin, operation):
            FreeCADGui.addCommand(name, command())
            names.append(name)
    return names
