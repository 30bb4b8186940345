# bezjoin workbench: smooth joins of Bezier curves (blend, round corner, merge,
# spline through on-curve points). Install: link or copy this folder into FreeCAD's
# Mod folder; see bezjoin_workbench/__init__.py for how the bindings are found.
import FreeCADGui


class BezjoinWorkbench(FreeCADGui.Workbench):
    MenuText = "Bezjoin"
    ToolTip = "Smooth joins of Bezier curves (bezjoin library)"

    def Initialize(self):
        from bezjoin_workbench import commands

        names = commands.register()
        self.appendToolbar("Bezjoin", names)
        self.appendMenu("Bezjoin", names)

    def GetClassName(self):
        return "Gui::PythonWorkbench"


FreeCADGui.addWorkbench(BezjoinWorkbench())
