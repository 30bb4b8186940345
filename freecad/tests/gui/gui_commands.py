"""GUI test of the bezjoin workbench in the real FreeCAD GUI (run under Xvfb by
``freecad/gui-test.sh``; not a ``test_*_in_freecad.py`` file, so the headless runner
``freecad/run-tests.sh`` does not pick it up).

FreeCAD runs this file as a macro once its main window is up:

    BEZJOIN_GUI_OUTPUT=/tmp/bezjoin-gui freecad freecad/tests/gui/gui_commands.py

What it does, as a user would:

* activates the Bezjoin workbench, loaded by FreeCAD from its user ``Mod`` folder
  (the runner links ``Mod/Bezjoin`` to this repository in a fresh HOME), so the
  commands are the ones ``InitGui.py`` registers;
* builds a PartDesign Body placed at (100, 0, 5), not the identity, holding sketches
  of lines (a closed rectangle, an open corner, two nearly collinear lines, a line and
  an arc, a polyline of points);
* runs each command with ``FreeCADGui.runCommand("Bezjoin_...")`` on a selection made
  with ``FreeCADGui.Selection.addSelection(doc.Name, sketch.Name, "EdgeN")`` (or
  ``"VertexN"``). The commands open their real modal Qt form (``commands.ask``); a
  timer fills in the values given here by label and clicks its OK button, as a user
  would (no hook in the workbench). A message box (an error of the command) fails the
  test;
* checks every result in model (global) coordinates: a parametric
  ``Part::FeaturePython`` with the right proxy, ``isValid()``, its shape valid and at
  x >= 100, z = 5, its ends where they must be (on the source edges' ends as placed
  by the Body), and that it recomputes when a parameter changes and when the Body
  moves;
* checks which sketches a consuming feature hides: one whose every edge it uses (the
  two-edge corner and merge sketches, the frame), and not one of which it uses some
  edges only (a merge of two edges of a three-edge sketch), whose other edges must
  stay in view;
* writes screenshots with ``ActiveView.saveImage`` into the folder named by
  ``BEZJOIN_GUI_OUTPUT`` (default ``/tmp/bezjoin-gui``) and checks they are not blank;
* then rounds a corner of a sketch in a rotated, placed ``App::Part``: the feature must
  land in that Part (the Body's results cannot: a Body takes PartDesign features
  only), be drawn where the sketch is, and hide the sketch.

FreeCAD's exit status says nothing about a macro, so the outcome goes to the result
file ``BEZJOIN_GUI_RESULT`` (default ``<output>/result.txt``): first line ``OK <n>
checks`` or ``FAILED``, then the details; the script then ends FreeCAD with
``os._exit``.
"""

import math
import os
import sys
import time
import traceback

import FreeCAD
import FreeCADGui
import Part
import Sketcher
from PySide import QtCore, QtGui

V = FreeCAD.Vector
OUTPUT = os.environ.get("BEZJOIN_GUI_OUTPUT") or "/tmp/bezjoin-gui"
RESULT = os.environ.get("BEZJOIN_GUI_RESULT") or os.path.join(OUTPUT, "result.txt")
#: The folder the workbench must be loaded from (the runner's Mod/Bezjoin link).
WORKBENCH = os.environ.get("BEZJOIN_GUI_WORKBENCH", "")
BODY_PLACEMENT = FreeCAD.Placement(V(100, 0, 5), FreeCAD.Rotation())
TOLERANCE = 1e-6

log_lines = []
checks = [0]


def log(message):
    log_lines.append(message)
    FreeCAD.Console.PrintMessage(f"bezjoin GUI test: {message}\n")


def check(condition, message):
    checks[0] += 1
    if not condition:
        raise AssertionError(message)


def close(a, b, tolerance=TOLERANCE):
    return a.distanceToPoint(b) <= tolerance


def model(point):
    """A sketch point (the sketches have the identity placement in the Body) in model
    coordinates."""
    return BODY_PLACEMENT.multVec(point) if isinstance(point, FreeCAD.Vector) else \
        BODY_PLACEMENT.multVec(V(*point))


# ------------------------------------------------------------------------ the model

def add_sketch(body, name, geometry):
    sketch = body.newObject("Sketcher::SketchObject", name)
    sketch.Support = None
    sketch.MapMode = "Deactivated"
    for element in geometry:
        sketch.addGeometry(element, False)
    # Join consecutive lines end to start (a real sketch's wires).
    for index in range(len(geometry) - 1):
        if close(geometry[index].EndPoint, geometry[index + 1].StartPoint):
            sketch.addConstraint(Sketcher.Constraint("Coincident", index, 2, index + 1, 1))
    return sketch


def polyline(points, closed=False):
    pairs = list(zip(points, points[1:] + (points[:1] if closed else [])))
    return [Part.LineSegment(V(*p), V(*q)) for p, q in pairs]


def edge_name(sketch, start, end):
    """The name of the edge of ``sketch`` (local coordinates) from ``start`` to ``end``
    (either way round)."""
    start, end = V(*start), V(*end)
    for index, edge in enumerate(sketch.Shape.Edges, 1):
        a, b = edge.Vertexes[0].Point, edge.Vertexes[-1].Point
        if (close(a, start) and close(b, end)) or (close(a, end) and close(b, start)):
            return f"Edge{index}"
    raise AssertionError(f"{sketch.Name} has no edge {start} - {end}")


def vertex_name(sketch, point):
    point = V(*point)
    for index, vertex in enumerate(sketch.Shape.Vertexes, 1):
        if close(vertex.Point, point):
            return f"Vertex{index}"
    raise AssertionError(f"{sketch.Name} has no vertex at {point}")


def build_model(doc):
    body = doc.addObject("PartDesign::Body", "Body")
    body.Placement = BODY_PLACEMENT
    frame_points = [(0, 0, 0), (40, 0, 0), (40, 30, 0), (0, 30, 0)]
    arc = Part.ArcOfCircle(Part.Circle(V(90, 15, 0), V(0, 0, 1), 10), -math.pi / 2, 0.0)
    sketches = {
        "Frame": add_sketch(body, "Frame", polyline(frame_points, closed=True)),
        "Corner": add_sketch(body, "Corner", polyline([(60, 40, 0), (90, 40, 0),
                                                       (90, 60, 0)])),
        "MergePair": add_sketch(body, "MergePair", polyline([(0, 50, 0), (20, 50, 0),
                                                             (45, 53, 0)])),
        "LineArc": add_sketch(body, "LineArc", [Part.LineSegment(V(60, 0, 0), V(80, 0, 0)),
                                                arc]),
        "Points": add_sketch(body, "Points", polyline([(0, 70, 0), (15, 80, 0), (30, 70, 0),
                                                       (45, 80, 0)])),
        "MergeOfThree": add_sketch(body, "MergeOfThree",
                                   polyline([(60, 70, 0), (75, 70, 0), (95, 72, 0),
                                             (95, 85, 0)])),
    }
    doc.recompute()
    for sketch in sketches.values():
        check(sketch.isValid() and not sketch.Shape.isNull(), f"{sketch.Name} did not build")
    # The sketches' shapes are local to the Body: the Body's placement is not the identity.
    check(close(sketches["Frame"].Shape.BoundBox.getPoint(0), V(0, 0, 0), 1e-6),
          "the sketch's Shape should be local to the Body (xmin 0)")
    return body, sketches


# ------------------------------------------------------------------ running commands

class FormFiller:
    """Watches for the command's modal form (or a message box) while ``runCommand``
    runs, fills in ``values`` (label prefix -> value) and clicks OK."""

    def __init__(self, values):
        self.values = dict(values)
        self.forms = []
        self.messages = []
        self.timer = QtCore.QTimer()
        self.timer.setInterval(50)
        self.timer.timeout.connect(self.poll)

    def __enter__(self):
        self.timer.start()
        return self

    def __exit__(self, *exc):
        self.timer.stop()
        return False

    @staticmethod
    def _open_dialog():
        widget = QtGui.QApplication.activeModalWidget()
        if isinstance(widget, QtGui.QDialog) and widget.isVisible():
            return widget
        for widget in QtGui.QApplication.topLevelWidgets():
            if isinstance(widget, QtGui.QDialog) and widget.isVisible() and widget.isModal():
                return widget
        return None

    def poll(self):
        dialog = self._open_dialog()
        if dialog is None:
            return
        if isinstance(dialog, QtGui.QMessageBox):
            self.messages.append(dialog.text())
            dialog.reject()
            return
        layout = dialog.layout()
        rows = {}
        if isinstance(layout, QtGui.QFormLayout):
            for row in range(layout.rowCount()):
                label = layout.itemAt(row, QtGui.QFormLayout.LabelRole)
                field = layout.itemAt(row, QtGui.QFormLayout.FieldRole)
                if label is not None and field is not None and label.widget() is not None:
                    rows[label.widget().text()] = field.widget()
        used = set()
        for prefix, value in self.values.items():
            matches = [(text, widget) for text, widget in rows.items()
                       if text.startswith(prefix)]
            if len(matches) != 1:
                self.messages.append(f"form {dialog.windowTitle()!r}: {len(matches)} fields "
                                     f"start with {prefix!r} (fields: {list(rows)})")
                continue
            widget = matches[0][1]
            if isinstance(widget, (QtGui.QDoubleSpinBox, QtGui.QSpinBox)):
                widget.setValue(value)
            elif isinstance(widget, QtGui.QCheckBox):
                widget.setChecked(bool(value))
            elif isinstance(widget, QtGui.QComboBox):
                widget.setCurrentIndex(widget.findText(value))
            used.add(prefix)
        self.forms.append((dialog.windowTitle(), list(rows)))
        box = dialog.findChild(QtGui.QDialogButtonBox)
        if box is None or box.button(QtGui.QDialogButtonBox.Ok) is None:
            self.messages.append(f"form {dialog.windowTitle()!r} has no OK button")
            dialog.reject()
            return
        box.button(QtGui.QDialogButtonBox.Ok).click()


def run_command(doc, name, selection, values=None, expect_form=True):
    """Select ``selection`` (``[(object, "EdgeN"), ...]`` in order), run the command
    ``name`` and return the one object it added."""
    FreeCADGui.Selection.clearSelection()
    for obj, sub in selection:
        FreeCADGui.Selection.addSelection(doc.Name, obj.Name, sub)
    picked = [(s.ObjectName, list(s.SubElementNames))
              for s in FreeCADGui.Selection.getSelectionEx()]
    check(sum(len(subs) for _name, subs in picked) == len(selection),
          f"{name}: the selection is {picked}")
    before = set(o.Name for o in doc.Objects)
    with FormFiller(values or {}) as filler:
        FreeCADGui.runCommand(name)
        # The form is modal: runCommand returns after it was accepted.
        for _ in range(20):
            QtGui.QApplication.processEvents()
    check(not filler.messages, f"{name}: {filler.messages}")
    if expect_form:
        check(len(filler.forms) == 1, f"{name}: expected its form once, saw {filler.forms}")
        log(f"{name}: form {filler.forms[0][0]!r} accepted with {values or 'defaults'}")
    else:
        check(not filler.forms, f"{name}: unexpected form {filler.forms}")
    added = [o for o in doc.Objects if o.Name not in before]
    check(len(added) == 1, f"{name}: added {[o.Name for o in added]}")
    return added[0]


def check_feature(obj, proxy_class):
    check(obj.TypeId == "Part::FeaturePython", f"{obj.Name} is a {obj.TypeId}")
    check(type(obj.Proxy).__name__ == proxy_class,
          f"{obj.Name}'s proxy is {type(obj.Proxy).__name__}")
    check(obj.isValid(), f"{obj.Name} is invalid: {obj.getStatusString()}")
    check(not obj.Shape.isNull() and obj.Shape.isValid(), f"{obj.Name}'s shape is not valid")
    check(obj.getParentGeoFeatureGroup() is None, f"{obj.Name} is not at the document root")
    # Drawn in the 3D view: a Part::FeaturePython with no view provider proxy at all gets
    # no display mode in FreeCAD 0.20 and shows nothing (ViewObject.Proxy = 0 selects
    # Part's own view provider).
    view = obj.ViewObject
    check(view is not None and view.Visibility and
          view.getEnumerationsOfProperty("DisplayMode") and view.DisplayMode,
          f"{obj.Name} is not drawn in the 3D view: its view provider has no display mode "
          f"(modes {view.getEnumerationsOfProperty('DisplayMode') if view else None}; "
          "features.py should set obj.ViewObject.Proxy = 0 in the GUI)")
    box = obj.Shape.BoundBox
    check(box.XMin >= 100 - 1e-6, f"{obj.Name} starts at x = {box.XMin} (not in model "
                                  "coordinates: the Body is at x = 100)")
    check(abs(box.ZMin - 5) < 1e-6 and abs(box.ZMax - 5) < 1e-6,
          f"{obj.Name} at z = {box.ZMin}..{box.ZMax}, not 5")
    log(f"{obj.Label}: {proxy_class}, valid, bound box x {box.XMin:.3f}..{box.XMax:.3f} "
        f"y {box.YMin:.3f}..{box.YMax:.3f} z {box.ZMin:.3f}")


def ends(shape):
    edges = Part.__sortEdges__(shape.Edges) if len(shape.Edges) > 1 else shape.Edges
    wire = Part.Wire(edges)
    return wire.OrderedVertexes[0].Point, wire.OrderedVertexes[-1].Point


def same_ends(shape, p, q, what):
    a, b = ends(shape)
    ok = (close(a, p) and close(b, q)) or (close(a, q) and close(b, p))
    check(ok, f"{what}: ends {a}, {b}; expected {p}, {q}")


# ------------------------------------------------------------------------ the tests

def test_spline(doc, sketches):
    points = [(0, 70, 0), (15, 80, 0), (30, 70, 0), (45, 80, 0)]
    sketch = sketches["Points"]
    obj = run_command(doc, "Bezjoin_Spline", [(sketch, vertex_name(sketch, p)) for p in points],
                      expect_form=False)
    check_feature(obj, "SplineFeature")
    for point in points:
        distance = obj.Shape.distToShape(Part.Vertex(model(point)))[0]
        check(distance < 1e-6, f"the spline misses {model(point)} by {distance}")
    return obj


def test_blend(doc, sketches):
    sketch = sketches["LineArc"]
    line = edge_name(sketch, (60, 0, 0), (80, 0, 0))
    arc = edge_name(sketch, (90, 5, 0), (100, 15, 0))
    obj = run_command(doc, "Bezjoin_Blend", [(sketch, line), (sketch, arc)], {})
    check_feature(obj, "BlendFeature")
    # u0 = 1: the line's end; v0 = 0: the arc's start (its parameter range, in the
    # model: the Body's placement applied to the sketch's edges).
    arc_edge = sketch.Shape.getElement(arc)
    arc_start = model(arc_edge.valueAt(arc_edge.FirstParameter))
    same_ends(obj.Shape, model((80, 0, 0)), arc_start, "the blend")
    # Tangent to the line at its end (at least G1 there).
    edge = obj.Shape.Edges[0]
    start, end = edge.valueAt(edge.FirstParameter), edge.valueAt(edge.LastParameter)
    at_line = edge.FirstParameter if close(start, model((80, 0, 0))) else edge.LastParameter
    tangent = edge.tangentAt(at_line)
    check(abs(tangent.y) < 1e-6 and abs(tangent.z) < 1e-6,
          f"the blend is not tangent to the line: {tangent}")
    return obj


def test_round_corner(doc, sketches):
    sketch = sketches["Corner"]
    first = edge_name(sketch, (60, 40, 0), (90, 40, 0))
    second = edge_name(sketch, (90, 40, 0), (90, 60, 0))
    obj = run_command(doc, "Bezjoin_RoundCorner", [(sketch, first), (sketch, second)],
                      {"Setback along the first edge": 4.0,
                       "Setback along the second edge": 4.0})
    check_feature(obj, "RoundCornerFeature")
    check(abs(obj.Setback.Value - 4.0) < 1e-9, f"Setback stored as {obj.Setback}")
    same_ends(obj.Shape, model((60, 40, 0)), model((90, 60, 0)), "the rounded corner")
    corner = Part.Vertex(model((90, 40, 0)))
    distance = obj.Shape.distToShape(corner)[0]
    check(distance > 0.5, f"the rounded corner passes {distance} from the sharp corner")
    check(obj.Shape.isClosed() is False or len(obj.Shape.Wires) == 1,
          "the rounded corner is not one path")
    # Parametric: a larger setback cuts more.
    obj.Setback = 8.0
    obj.SecondSetback = 8.0
    doc.recompute()
    check(obj.isValid(), f"after Setback = 8: {obj.getStatusString()}")
    farther = obj.Shape.distToShape(corner)[0]
    check(farther > distance + 0.5, f"Setback 8 passes {farther} from the corner (4: "
                                    f"{distance})")
    log(f"round corner: {distance:.3f} from the corner with setback 4, {farther:.3f} with 8")
    check(not sketch.ViewObject.Visibility,
          "the rounded corner did not hide its sketch (it uses both its edges)")
    return obj


def test_merge(doc, sketches):
    sketch = sketches["MergePair"]
    first = edge_name(sketch, (0, 50, 0), (20, 50, 0))
    second = edge_name(sketch, (20, 50, 0), (45, 53, 0))
    obj = run_command(doc, "Bezjoin_Merge", [(sketch, first), (sketch, second)], {})
    check_feature(obj, "MergeFeature")
    check(len(obj.Shape.Edges) == 1, f"the merge has {len(obj.Shape.Edges)} edges")
    same_ends(obj.Shape, model((0, 50, 0)), model((45, 53, 0)), "the merged edge")
    deviation = obj.Shape.distToShape(Part.Vertex(model((20, 50, 0))))[0]
    check(deviation < 2.0, f"the merged edge passes {deviation} from the join")
    log(f"merge: ends kept, {deviation:.3f} from the join, MergeMu {obj.MergeMu:.4f}")
    check(not sketch.ViewObject.Visibility,
          "the merge did not hide its sketch (it uses both its edges)")
    return obj


def test_merge_of_part_of_a_sketch(doc, sketches):
    """A merge of two of a sketch's three edges leaves the sketch in view: hiding it
    would hide its third edge too (user testing, session 40)."""
    sketch = sketches["MergeOfThree"]
    first = edge_name(sketch, (60, 70, 0), (75, 70, 0))
    second = edge_name(sketch, (75, 70, 0), (95, 72, 0))
    obj = run_command(doc, "Bezjoin_Merge", [(sketch, first), (sketch, second)], {})
    check_feature(obj, "MergeFeature")
    check(obj.ConsumeSources, f"{obj.Name} does not consume its sources")
    check(sketch.ViewObject.Visibility,
          "the merge of two of three edges hid its sketch, and the third edge with it")
    # Switching ConsumeSources off and on again keeps it in view too.
    obj.ConsumeSources = False
    check(sketch.ViewObject.Visibility, "ConsumeSources off did not show the sketch")
    obj.ConsumeSources = True
    check(sketch.ViewObject.Visibility,
          "ConsumeSources on hid a sketch the merge uses two of three edges of")
    log("merge of two of three edges: the sketch stays visible")
    return obj


def test_round_wire(doc, body, sketches):
    sketch = sketches["Frame"]
    corners = [(0, 0, 0), (40, 0, 0), (40, 30, 0), (0, 30, 0)]
    names = [edge_name(sketch, p, q) for p, q in zip(corners, corners[1:] + corners[:1])]
    obj = run_command(doc, "Bezjoin_RoundWireByRadius", [(sketch, n) for n in names],
                      {"Radius": 5.0})
    check_feature(obj, "RoundWireFeature")
    check(abs(obj.Radius.Value - 5.0) < 1e-9, f"Radius stored as {obj.Radius}")

    def check_rounded(radius, dx):
        shape = obj.Shape
        check(len(shape.Wires) == 1 and shape.Wires[0].isClosed(),
              f"radius {radius}: not one closed wire")
        box = shape.BoundBox
        for got, want, what in ((box.XMin, 100 + dx, "xmin"), (box.XMax, 140 + dx, "xmax"),
                                (box.YMin, 0, "ymin"), (box.YMax, 30, "ymax")):
            check(abs(got - want) < 1e-6, f"radius {radius}: {what} {got}, expected {want}")
        face = Part.Face(shape.Wires[0])
        check(face.isValid(), f"radius {radius}: Part.Face of the wire is not valid")
        # The four corners cut off, but less than by arcs of the radius (a G2 blend
        # touches the edges where the arc does and bends more gently near them; it
        # lies between the arc and the corner).
        arc_cut = (4 - math.pi) * radius ** 2
        arc_area = 40 * 30 - arc_cut
        check(arc_area - 1e-6 <= face.Area <= 40 * 30 - 0.3 * arc_cut,
              f"radius {radius}: area {face.Area}; arcs give {arc_area}, no rounding 1200")
        for corner in corners:
            point = BODY_PLACEMENT.multVec(V(*corner)) + V(dx, 0, 0)
            distance = shape.distToShape(Part.Vertex(point))[0]
            check(distance > 0.3 * radius, f"radius {radius}: {distance} from {point}")
        log(f"round wire radius {radius} (Body x = {100 + dx}): closed, face area "
            f"{face.Area:.3f} (arcs {arc_area:.3f}), MaxArcDeviation "
            f"{obj.MaxArcDeviation:.4f}")

    check_rounded(5.0, 0)
    obj.Radius = 3.0
    doc.recompute()
    check(obj.isValid(), f"after Radius = 3: {obj.getStatusString()}")
    check_rounded(3.0, 0)
    # Moving the Body moves the result (Containers dependency).
    body.Placement = FreeCAD.Placement(V(120, 0, 5), FreeCAD.Rotation())
    doc.recompute()
    check(obj.isValid(), f"after moving the Body: {obj.getStatusString()}")
    check_rounded(3.0, 20)
    body.Placement = BODY_PLACEMENT
    obj.Radius = 5.0
    doc.recompute()
    check(obj.isValid(), f"after moving back: {obj.getStatusString()}")
    check_rounded(5.0, 0)
    if FreeCAD.GuiUp:
        check(not sketch.ViewObject.Visibility, "the rounded frame did not hide its sketch")
    return obj


def test_round_corner_in_a_part(doc):
    """A sketch in a rotated, placed App::Part: the command's feature goes into that Part
    (the Body's features cannot: a Body takes PartDesign features only), is drawn where
    the sketch is (its shape local to the Part), and hides its sketch."""
    part = doc.addObject("App::Part", "Assembly")
    part.Placement = FreeCAD.Placement(V(0, -80, 5), FreeCAD.Rotation(V(0, 0, 1), 30))
    sketch = doc.addObject("Sketcher::SketchObject", "PartCorner")
    part.addObject(sketch)
    for element in polyline([(0, 0, 0), (30, 0, 0), (30, 20, 0)]):
        sketch.addGeometry(element, False)
    sketch.addConstraint(Sketcher.Constraint("Coincident", 0, 2, 1, 1))
    doc.recompute()
    obj = run_command(doc, "Bezjoin_RoundCorner", [(sketch, edge_name(sketch, (0, 0, 0), (30, 0, 0))),
                                                   (sketch, edge_name(sketch, (30, 0, 0), (30, 20, 0)))],
                      {"Setback along the first edge": 4.0,
                       "Setback along the second edge": 4.0})
    check(obj.getParentGeoFeatureGroup() == part,
          f"{obj.Name} is in {obj.getParentGeoFeatureGroup()}, not in the Part of its sketch")
    check(obj.isValid(), f"{obj.Name} is invalid: {obj.getStatusString()}")
    check(part not in list(obj.Containers), "the feature depends on its own Part (a cycle)")
    # Model coordinates: the Part's placement on top of the local shape.
    shape = obj.Shape.copy()
    shape.Placement = obj.getGlobalPlacement()
    in_model = part.Placement.multVec
    same_ends(shape, in_model(V(0, 0, 0)), in_model(V(30, 20, 0)), "the corner in the Part")
    distance = shape.distToShape(Part.Vertex(in_model(V(30, 0, 0))))[0]
    check(distance > 0.5, f"the corner in the Part passes {distance} from the sharp corner")
    view = obj.ViewObject
    check(view is not None and view.Visibility and view.DisplayMode,
          f"{obj.Name} in the Part is not drawn")
    check(not sketch.ViewObject.Visibility, "the corner in the Part did not hide its sketch")
    log(f"round corner in an App::Part: in {part.Name}, {distance:.3f} from the corner")
    return obj


def screenshot(name, orientation):
    view = FreeCADGui.ActiveDocument.ActiveView
    getattr(view, orientation)()
    view.fitAll()
    for _ in range(10):
        QtGui.QApplication.processEvents()
    path = os.path.join(OUTPUT, name)
    if os.path.exists(path):
        os.remove(path)
    view.saveImage(path, 1280, 960, "White")
    check(os.path.isfile(path) and os.path.getsize(path) > 1000, f"no screenshot at {path}")
    image = QtGui.QImage(path)
    check(not image.isNull(), f"{path} is not an image")
    # Dark pixels (the results' black edges on white; the sketches' edges are white).
    gray = image.convertToFormat(QtGui.QImage.Format_Grayscale8)
    width, height, stride = gray.width(), gray.height(), gray.bytesPerLine()
    data = bytes(gray.constBits())[:stride * height]
    drawn = sum(1 for y in range(height) for value in data[y * stride:y * stride + width]
                if value < 200)
    check(drawn > 2000, f"{path} is nearly blank ({drawn} dark pixels)")
    log(f"screenshot {path} ({width}x{height}, {drawn} dark pixels)")


def main():
    started = time.time()
    os.makedirs(OUTPUT, exist_ok=True)
    check(FreeCAD.GuiUp and FreeCADGui.getMainWindow() is not None, "no FreeCAD GUI")
    check("BezjoinWorkbench" in FreeCADGui.listWorkbenches(),
          "the Bezjoin workbench is not installed in FreeCAD's Mod folder")
    FreeCADGui.activateWorkbench("BezjoinWorkbench")
    import bezjoin_workbench  # noqa: PLC0415 (loaded by the workbench)

    where = os.path.realpath(bezjoin_workbench.__file__)
    log(f"workbench from {where}")
    if WORKBENCH:
        check(where.startswith(os.path.realpath(WORKBENCH) + os.sep),
              f"the workbench comes from {where}, not from {WORKBENCH}")
    bezjoin = bezjoin_workbench.ensure_bindings_importable()
    log(f"library {bezjoin._library.library_path()}")
    registered = FreeCADGui.listCommands()
    for name in ("Bezjoin_Blend", "Bezjoin_RoundCorner", "Bezjoin_RoundWireByRadius",
                 "Bezjoin_Merge", "Bezjoin_Spline"):
        check(name in registered, f"{name} is not registered")

    doc = FreeCAD.newDocument("BezjoinGui")
    FreeCADGui.activeDocument().activeView()
    body, sketches = build_model(doc)
    test_spline(doc, sketches)
    test_blend(doc, sketches)
    test_round_corner(doc, sketches)
    test_merge(doc, sketches)
    test_merge_of_part_of_a_sketch(doc, sketches)
    test_round_wire(doc, body, sketches)
    doc.recompute()
    for obj in doc.Objects:
        check(obj.isValid(), f"{obj.Name} is invalid: {obj.getStatusString()}")
    screenshot("bezjoin-gui-top.png", "viewTop")
    screenshot("bezjoin-gui-isometric.png", "viewIsometric")
    # After the screenshots (a Part far from the Body would shrink them).
    test_round_corner_in_a_part(doc)
    doc.recompute()
    for obj in doc.Objects:
        check(obj.isValid(), f"{obj.Name} is invalid: {obj.getStatusString()}")
    log(f"done in {time.time() - started:.1f} s")


def finish():
    status = 1
    try:
        main()
        report = f"OK {checks[0]} checks\n"
        status = 0
    except BaseException:  # noqa: BLE001 (FreeCAD would only print it)
        report = "FAILED\n" + traceback.format_exc()
    try:
        os.makedirs(os.path.dirname(RESULT) or ".", exist_ok=True)
        with open(RESULT + ".tmp", "w", encoding="utf-8") as handle:
            handle.write(report)
            handle.write("".join(line + "\n" for line in log_lines))
        os.replace(RESULT + ".tmp", RESULT)
    finally:
        sys.stdout.write(report)
        sys.stdout.flush()
        sys.stderr.flush()
        # FreeCAD's exit status and shutdown are not reliable: leave at once.
        os._exit(status)


# Run from the event loop once the main window is up (FreeCAD executes this file while
# it is still starting).
QtCore.QTimer.singleShot(0, finish)
