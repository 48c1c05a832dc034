# MeshRound workbench registration.  FreeCAD runs this only when the GUI is up, with this folder on
# sys.path.  It stays light: commands (and with them numpy and the compiled engine) are imported only
# when the workbench is first activated.
#
# FreeCAD exec()s this file inside a function, so top-level names are not visible from methods or the
# class body: everything a method needs is imported in it.
import FreeCADGui


class MeshRoundWorkbench(FreeCADGui.Workbench):
    MenuText = "MeshRound"
    ToolTip = "Round sharp edges of triangle meshes with a rolling ball"

    def __init__(self):
        import importlib.util
        import os
        # no reliable __file__ here: find the package without importing it
        package_dir = os.path.dirname(importlib.util.find_spec("MeshRound").origin)
        self.__class__.Icon = os.path.join(os.path.dirname(package_dir), "Resources", "icons",
                                           "MeshRound.svg")

    def Initialize(self):
        import MeshRoundGui  # registers the commands
        names = list(MeshRoundGui.COMMANDS)
        self.appendToolbar("MeshRound", names)
        self.appendMenu("&MeshRound", names)

    def GetClassName(self):
        return "Gui::PythonWorkbench"


FreeCADGui.addWorkbench(MeshRoundWorkbench())
