"""Paths of the workbench's own files (icons), wherever Mod/MeshRound was installed or linked."""
import os

MOD_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # .../Mod/MeshRound
ICON_DIR = os.path.join(MOD_DIR, "Resources", "icons")


def icon_path(name):
    """Absolute path of Resources/icons/<name> (name with or without the .svg suffix)."""
    if not os.path.splitext(name)[1]:
        name += ".svg"
    return os.path.join(ICON_DIR, name)
