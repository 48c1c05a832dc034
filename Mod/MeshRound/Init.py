# MeshRound: rounds sharp edges of triangle meshes with a rolling ball.
#
# FreeCAD runs this file at start-up, GUI or not, with this folder on sys.path.  Nothing needs
# registering for console use: `import MeshRound` gives the API (MeshRound.round_edges, make_rounding).
# The workbench itself is registered in InitGui.py.
