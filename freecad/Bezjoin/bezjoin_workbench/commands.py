"""Thin GUI commands over :mod:`bezjoin_workbench.operations`.

Each command reads the selection, asks for its parameters in a small form,
calls the plain operation (so errors show before anything is made), and adds a
parametric feature (:mod:`bezjoin_workbench.features`) linked to the selected
objects and edges, with the form's values as its properties; it recomputes when a
source or a parameter changes. Errors (unsupported geometry, the library's status
and message) are shown in a message box and the report view; nothing is created
then. Edges that come from no document object (``inputs`` without ``links``, as
macros and the headless tests give) get a plain ``Part::Feature`` as before.
"""

import FreeCAD
import FreeCADGui
from PySide import QtGui

from . import features, operations
from .operations import bezjoin


class SelectionError(Exception):
    """The selection does not fit the command."""


def _selection(selections):
    return FreeCADGui.Selection.getSelectionEx() if selections is None else selections


def _record(links, found):
    """Put ``found`` into the caller's ``links`` list (when one is given)."""
    if links is not None:
        links[:] = found


def _sub_names(selection, shape_type):
    return [name for name, sub in zip(selection.SubElementNames, selection.SubObjects)
            if sub.ShapeType == shape_type]


def _sub_elements(selection, shape_type):
    """The picked sub-elements of ``shape_type`` in model (global) coordinates: a sketch
    inside a placed Body or Part is moved by the containers' placements."""
    names = _sub_names(selection, shape_type)
    if not names:
        return []
    return operations.model_shape(selection.Object, names)


def selected_edges(count, selections=None, links=None):
    """Exactly ``count`` edges from the selection, in the order they were picked
    (sub-elements, or objects whose shape is a single edge), in model coordinates.
    ``links`` (a list) receives where they come from: one link value ``(object,
    [edge name])`` per edge (``[]``: the object's single edge), for the features."""
    edges, found = [], []
    for selection in _selection(selections):
        if selection.SubObjects:
            edges.extend(_sub_elements(selection, "Edge"))
            found.extend((selection.Object, [name])
                         for name in _sub_names(selection, "Edge"))
        elif hasattr(selection.Object, "Shape") and len(selection.Object.Shape.Edges) == 1:
            edges.append(operations.model_shape(selection.Object).Edges[0])
            found.append((selection.Object, []))
    if len(edges) != count:
        raise SelectionError(f"select exactly {count} edges (found {len(edges)})")
    _record(links, found)
    return edges


def selected_path(selections=None, links=None):
    """The edges of one selected wire (in its order), or picked edges in the order
    they were picked (at least two), in model coordinates. ``links`` (a list)
    receives the sources: ``[(object, [])]`` for a whole wire, else ``(object, [edge
    names])`` per selected object."""
    selections = _selection(selections)
    edges = [e for sel in selections for e in _sub_elements(sel, "Edge")]
    found = [(sel.Object, _sub_names(sel, "Edge")) for sel in selections
             if _sub_names(sel, "Edge")]
    if not edges and len(selections) == 1 and hasattr(selections[0].Object, "Shape"):
        try:
            edges = operations.path_edges(operations.model_shape(selections[0].Object))
            found = [(selections[0].Object, [])]
        except bezjoin.BezjoinError:
            edges = []
    if len(edges) < 2:
        raise SelectionError("select one wire (a sketch, a polyline...) or its edges in path "
                             f"order (found {len(edges)} edges)")
    _record(links, found)
    return edges


def selected_points(selections=None, links=None):
    """On-curve points: picked vertices in order, or the ordered vertices of one
    selected wire (a polyline through the points), in model coordinates. ``links``
    (a list) receives the sources, as for :func:`selected_path`."""
    selections = _selection(selections)
    vertices = [v for sel in selections for v in _sub_elements(sel, "Vertex")]
    if vertices:
        _record(links, [(sel.Object, _sub_names(sel, "Vertex")) for sel in selections
                        if _sub_names(sel, "Vertex")])
        return [v.Point for v in vertices]
    if len(selections) == 1 and hasattr(selections[0].Object, "Shape"):
        wires = operations.model_shape(selections[0].Object).Wires
        if len(wires) == 1:
            _record(links, [(selections[0].Object, [])])
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
            widget.setRange(extra, MAX_ORDER)
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


#: The highest order offered in the forms: a blend of orders p and q has degree
#: p + q + 1, at most OpenCASCADE's 25 (larger sums are refused by the operations).
MAX_ORDER = (operations.MAX_BEZIER_DEGREE - 1) // 2

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


def _links(command, document):
    """The source links the command's selection reader recorded, or None for bare edges
    (``inputs`` replaced) and for sources in another document than ``document`` (no
    links across documents)."""
    links = command.links
    if not links or any(obj.Document != document for obj, _names in links):
        return None
    return links


def _order_properties(parameters):
    """The form's orders and scales as feature properties (-1: the curve's degree)."""
    def order(key):
        value = parameters.get(key)
        return -1 if value is None else value
    auto_scale = parameters.get("auto_scale")
    automatic = auto_scale is True or (auto_scale is None and parameters.get("p_scale") is None
                                       and parameters.get("q_scale") is None)
    properties = dict(POrder=order("p_order"), QOrder=order("q_order"), AutoScale=automatic)
    if parameters.get("p_scale") is not None:
        properties["PScale"] = parameters["p_scale"]
    if parameters.get("q_scale") is not None:
        properties["QScale"] = parameters["q_scale"]
    return properties


class Command:
    """Common frame: selection, form, operation, feature, error display."""

    title = ""
    tooltip = ""
    fields = []
    #: Where the selected edges or points come from (see :func:`selected_edges`).
    links = []

    def GetResources(self):  # noqa: N802 (FreeCAD's name)
        return {"MenuText": self.title, "ToolTip": self.tooltip}

    def IsActive(self):  # noqa: N802 (FreeCAD's name)
        return FreeCAD.ActiveDocument is not None

    def Activated(self):  # noqa: N802 (FreeCAD's name)
        document = FreeCAD.ActiveDocument
        self.links = []  # filled by the selection readers of inputs()
        try:
            inputs = self.inputs()
            self.check(inputs)  # before the form: nothing to fill in for a bad selection
            fields = self.fields_for(inputs)
            parameters = ask(self.title, fields) if fields else {}
            if parameters is None:
                return
            document.openTransaction(self.title)
            try:
                self.run(document, inputs, parameters)
            finally:
                document.commitTransaction()
            document.recompute()
        except (SelectionError, bezjoin.BezjoinError, bezjoin.UnsupportedGeometryError,
                bezjoin.LibraryNotFoundError, features.FeatureError) as error:
            FreeCAD.Console.PrintError(f"{self.title}: {error}\n")
            QtGui.QMessageBox.warning(FreeCADGui.getMainWindow(), self.title, str(error))

    def inputs(self):
        """Two selected edges (the spline command overrides this)."""
        return selected_edges(2, links=self.links)

    def check(self, inputs):
        """Refuse unsupported or repeated edges before the form opens."""
        operations.check_edges(inputs)

    def fields_for(self, inputs):
        """The form's fields, with defaults fitted to the selection."""
        return self.fields


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
        links = _links(self, document)
        if links is None:
            return operations.add_feature(document, "Blend", shape)
        return features.make_blend(document, links[0], links[1], U0=parameters.get("u0", 1.0),
                                   V0=parameters.get("v0", 0.0), **_order_properties(parameters))


class RoundCornerCommand(Command):
    title = "Round corner"
    tooltip = "Round the corner between two Bezier edges (bezjoin fillet)"
    fields = [
        ("method", "Method (Setback: the setbacks below; Radius: where the circular fillet "
                   "of the radius touches the edges)", "choice", "Setback",
         ("Setback", "Radius")),
        ("setback", "Setback along the first edge", "float", 1.0, (1e-9, 1e9)),
        ("second_setback", "Setback along the second edge", "float", 1.0, (1e-9, 1e9)),
        ("radius", "Radius (method Radius)", "float", 1.0, (1e-9, 1e9)),
        ("order", "Geometric continuity G^k of the blend (method Radius; 1..6)", "int", 2, 1),
    ] + ORDER_FIELDS + [
        AUTO_SCALE_FIELD,
        ("reverse_first", "Reverse the first edge (crossing edges)", "bool", False, None),
        ("reverse_second", "Reverse the second edge (crossing edges)", "bool", False, None),
    ]

    def fields_for(self, inputs):
        setback = operations.default_setback(inputs)
        return [(key, label, kind, setback, extra)
                if key in ("setback", "second_setback", "radius")
                else (key, label, kind, default, extra)
                for key, label, kind, default, extra in self.fields]

    def run(self, document, inputs, parameters):
        parameters = dict(parameters)
        method = parameters.pop("method", "Setback")
        radius, order = parameters.pop("radius", None), parameters.pop("order", 2)
        reverse = {key: parameters.pop(key, False) for key in ("reverse_first",
                                                               "reverse_second")}
        if method == "Radius":
            shape = operations.round_corner(inputs[0], inputs[1], radius=radius, order=order,
                                            **reverse)
        else:
            shape = operations.round_corner(inputs[0], inputs[1], **parameters, **reverse)
        links = _links(self, document)
        if links is None:
            return operations.add_feature(document, "RoundedCorner", shape)
        properties = dict(Method=method, ReverseFirst=reverse["reverse_first"],
                          ReverseSecond=reverse["reverse_second"])
        if method == "Radius":
            properties.update(Radius=radius, Order=order)
        else:
            setback = parameters.get("setback")
            properties.update(Setback=operations.default_setback(inputs) if setback is None
                              else setback,
                              SecondSetback=parameters.get("second_setback") or 0.0,
                              **_order_properties(parameters))
        return features.make_round_corner(document, links[0], links[1], **properties)


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
        return selected_path(links=self.links)

    def fields_for(self, inputs):
        """The radius starts at ``operations.DEFAULT_SETBACK_FRACTION`` of the shortest
        edge (as the corner's setback and radius do), so it fits the model's size."""
        radius = operations.default_setback(getattr(inputs, "Edges", inputs))
        return [(key, label, kind, radius if key == "radius" else default, extra)
                for key, label, kind, default, extra in self.fields]

    def run(self, document, inputs, parameters):
        parameters = dict(parameters)
        closed_choice = parameters.pop("closed")
        closed = {"auto": None, "yes": True, "no": False}[closed_choice]
        rounded = operations.round_wire_by_radius(inputs, closed=closed, **parameters)
        FreeCAD.Console.PrintMessage(f"{self.title}: {rounded.describe()}\n")
        links = _links(self, document)
        if links is None:
            return operations.add_feature(document, "RoundedWire", rounded.shape, {
                "FilletRadius": parameters["radius"],
                "MaxArcDeviation": rounded.max_arc_deviation})
        return features.make_round_wire(document, links, Method="Radius",
                                        Radius=parameters["radius"],
                                        Continuity=f"G{parameters.get('order', 2)}",
                                        Closed=closed_choice)


class MergeCommand(Command):
    title = "Merge two edges"
    tooltip = "Replace two consecutive Bezier edges by one Bezier edge (bezjoin merge)"
    fields = [
        ("metric", "Metric", "choice", "discrete", ("discrete", "l2")),
        ("mu_mode", "Split parameter mu", "choice", "optimal", ("half", "polygon", "optimal",
                                                                "given")),
        ("mu", "mu (when given)", "float", 0.5, (1e-6, 1 - 1e-6)),
        ("fix_ends", "Keep the outer end points", "bool", True, None),
        ("max_angle", "Largest angle between the edges at the join (degrees)", "float",
         operations.MAX_MERGE_ANGLE_DEGREES, (0.0, 180.0)),
        ("max_gap", "Largest gap between the edges' ends that the merge bridges (0: the "
                    "ends must touch)", "float", 0.0, (0.0, 1e9)),
        ("keep_first", "Keep the first edge unchanged", "bool", False, None),
        ("keep_second", "Keep the second edge unchanged", "bool", False, None),
    ]

    def run(self, document, inputs, parameters):
        parameters = dict(parameters)
        mode, mu = parameters.pop("mu_mode"), parameters.pop("mu")
        max_gap = parameters.pop("max_gap", 0.0) or 0.0
        merged = operations.merge_edges(inputs[0], inputs[1], mu=mu if mode == "given" else mode,
                                        max_gap=max_gap or "touching", **parameters)
        FreeCAD.Console.PrintMessage(f"{self.title}: {merged.describe()}\n")
        links = _links(self, document)
        if links is None:
            return operations.add_feature(document, "Merged", merged.shape, {
                "MergeMu": merged.mu, "MergeMetric": merged.metric_value,
                "MergeMaxDeviation": merged.max_deviation})
        max_angle = parameters.get("max_angle", operations.MAX_MERGE_ANGLE_DEGREES)
        return features.make_merge(
            document, links[0], links[1], Metric=parameters.get("metric", "discrete"),
            MuMode=mode, Mu=mu, FixEnds=parameters.get("fix_ends", True),
            MaxAngle=180.0 if max_angle is None else max_angle, MaxGap=max_gap,
            KeepFirst=parameters.get("keep_first", False),
            KeepSecond=parameters.get("keep_second", False))


class SplineCommand(Command):
    title = "Spline through on-curve points"
    tooltip = ("C1 cubic spline whose Bezier segments pass through the selected points: "
               "node, two inner points, node, then inner point and node per segment")
    fields = []

    def inputs(self):
        return selected_points(links=self.links)

    def check(self, inputs):
        """Points: the operation checks their count."""

    def run(self, document, inputs, parameters):
        shape = operations.spline_through_points(inputs)
        links = _links(self, document)
        if links is None:
            return operations.add_feature(document, "OnCurveSpline", shape)
        return features.make_spline(document, links)


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
