"""Registers the MeshRound workbench's GUI commands (imported by the workbench's Initialize).

FreeCAD records `import <the module that called FreeCADGui.addCommand>` at the top of every macro that
runs a command, by the module's file name.  That is why the registration lives in this top-level module
(this folder is on sys.path inside FreeCAD), so recorded macros run again as they are: keep its name.
Without the GUI (a macro replayed in freecadcmd) importing it does nothing.
"""
import FreeCAD

if FreeCAD.GuiUp:
    import FreeCADGui

    from MeshRound.commands import COMMANDS

    for _name, _command in COMMANDS.items():
        FreeCADGui.addCommand(_name, _command)
