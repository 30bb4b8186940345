"""The workbench glue: finding the bindings, edge conversion messages, orientation,
features, and the GUI commands driven headless (selection and form replaced)."""

import os
import unittest

import FreeCAD
import FreeCADGui
import Part

import bezjoin
import bezjoin_workbench
from bezjoin_workbench import commands, operations
from judge import bezier

V = FreeCAD.Vector
REPOSITORY = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class FindingTheBindings(unittest.TestCase):
    def test_repository_bindings_come_after_the_environment_variable(self):
        folders = bezjoin_workbench.binding_folders()
        self.assertIn(os.path.join(REPOSITORY, "bindings", "python"), folders)
        previous = os.environ.get("BEZJOIN_PYTHON_PATH")
        os.environ["BEZJOIN_PYTHON_PATH"] = "/elsewhere"
        try:
            self.assertEqual(bezjoin_workbench.binding_folders()[0], "/elsewhere")
        finally:
            if previous is None:
                del os.environ["BEZJOIN_PYTHON_PATH"]
            else:
                os.environ["BEZJOIN_PYTHON_PATH"] = previous

    def test_the_workbench_uses_the_repository_package(self):
        self.assertIs(operations.bezjoin, bezjoin)
        self.assertTrue(bezjoin.__file__.startswith(os.path.join(REPOSITORY, "bindings")))


class EdgeConversion(unittest.TestCase):
    def test_unsupported_edge_is_named(self):
        with self.assertRaises(bezjoin.UnsupportedGeometryError) as caught:
            operations.edge_curve(
                Part.OffsetCurve(Part.Circle(), 0.5, FreeCAD.Vector(0, 0, 1)).toShape(),
                "second edge")
        self.assertTrue(str(caught.exception).startswith("second edge: "), caught.exception)
        self.assertIn("OffsetCurve", str(caught.exception))

    def test_orientation_puts_the_nearest_ends_together(self):
        a = bezier([(0, 0, 0), (1, 1, 0), (2, 0, 0)])
        b = bezier([(5, 5, 0), (3, 1, 0), (2, 0, 0)])
        for first, second in ((a, b), (b, a)):
            with operations.edge_curve(first, "first") as p, \
                    operations.edge_curve(second, "second") as q:
                p_oriented, q_oriented = operations.orient_end_to_start(p, q)
                with p_oriented, q_oriented:
                    self.assertEqual(p_oriented.points[-1], q_oriented.points[0])
                    self.assertEqual(sorted(p_oriented.points), sorted(p.points))
                    self.assertEqual(sorted(q_oriented.points), sorted(q.points))


class Features(unittest.TestCase):
    def test_feature_holds_the_shape_and_report_properties(self):
        document = FreeCAD.newDocument("BezjoinFeatures")
        try:
            points = [(0.0, 0.0, 0.0), (1.0, 2.0, 0.0), (3.0, 0.0, 0.0)]
            edge = Part.Edge(bezier(points))
            feature = operations.add_feature(document, "Blend", edge, {"MergeMu": 0.25})
            document.recompute()
            self.assertEqual(feature.TypeId, "Part::Feature")
            self.assertEqual(feature.MergeMu, 0.25)
            self.assertEqual([tuple(p) for p in feature.Shape.Edges[0].Curve.getPoles()], points)
        finally:
            FreeCAD.closeDocument(document.Name)


class Commands(unittest.TestCase):
    """The GUI commands with the selection and the form replaced (no GUI here)."""

    def test_only_operations_the_bindings_expose_are_registered(self):
        registered = {}
        original = getattr(FreeCADGui, "addCommand", None)
        FreeCADGui.addCommand = lambda name, command: registered.setdefault(name, command)
        try:
            names = commands.register()
        finally:
            if original is None:
                del FreeCADGui.addCommand
            else:
                FreeCADGui.addCommand = original
        # The four commands of issue 9 and the wire fillet by radius of issue 18, with
        # the operation each one runs.
        expected = ["Bezjoin_Blend", "Bezjoin_RoundCorner", "Bezjoin_RoundWireByRadius",
                    "Bezjoin_Merge", "Bezjoin_Spline"]
        self.assertEqual(names, expected)
        self.assertEqual(sorted(registered), sorted(expected))
        operations_run = {name: operation for name, (_c, operation) in commands.COMMANDS.items()}
        self.assertEqual(operations_run, {"Bezjoin_Blend": "connect",
                                          "Bezjoin_RoundCorner": "fillet",
                                          "Bezjoin_RoundWireByRadius": "fillet_radius_chain",
                                          "Bezjoin_Merge": "merge",
                                          "Bezjoin_Spline": "lagrange_spline"})
        for operation in operations_run.values():
            self.assertTrue(callable(getattr(bezjoin, operation, None)), operation)
        menu_texts = [registered[name].GetResources()["MenuText"] for name in expected]
        self.assertEqual(menu_texts, ["Blend two edges", "Round corner",
                                      "Round wire corners by radius", "Merge two edges",
                                      "Spline through on-curve points"])
        for command in registered.values():
            resources = command.GetResources()
            self.assertTrue(resources["MenuText"])
            self.assertTrue(resources["ToolTip"])
            names_in_form = [field[0] for field in command.fields]
            self.assertEqual(len(names_in_form), len(set(names_in_form)))

    def test_scaled_commands_default_to_the_automatic_scale(self):
        # Issue 18: the forms of the commands with shape scales start with the
        # automatic scale checked (the default that never loops).
        for command in (commands.BlendCommand, commands.RoundCornerCommand):
            defaults = {key: default for key, _label, _kind, default, _extra in command.fields}
            self.assertIs(defaults["auto_scale"], True, command.title)


class OrientationTies(unittest.TestCase):
    def test_closed_pair_keeps_the_given_directions(self):
        # both ends coincide pairwise (a closed loop of two edges): no reversal
        a = bezier([(0, 0, 0), (1, 1, 0), (2, 0, 0)])
        b = bezier([(2, 0, 0), (1, -1, 0), (0, 0, 0)])
        with operations.edge_curve(a, "first") as p, operations.edge_curve(b, "second") as q:
            p_oriented, q_oriented = operations.orient_end_to_start(p, q)
            with p_oriented, q_oriented:
                self.assertEqual(p_oriented.points, p.points)
                self.assertEqual(q_oriented.points, q.points)
