"""What both pictures' render scripts share: the camera, and running unattended under the GUI."""
import os
import traceback

import FreeCAD
import Mesh
import numpy as np
from pivy import coin


def set_camera(view, direction, focus, height):
    """Orthographic camera looking along `direction` (z up on screen); centred on `focus` with `height`
    mm of view, or fitted to what is shown when focus is None."""
    d = FreeCAD.Vector(*direction).normalize()
    z = -d
    x = FreeCAD.Vector(0, 0, 1).cross(z).normalize()
    y = z.cross(x)
    q = FreeCAD.Rotation(FreeCAD.Matrix(x.x, y.x, z.x, 0, x.y, y.y, z.y, 0, x.z, y.z, z.z, 0, 0, 0, 0, 1)).Q
    cam = view.getCameraNode()
    cam.orientation.setValue(coin.SbRotation(*q))
    if focus is None:
        view.fitAll()
        return
    cam.position.setValue(coin.SbVec3f(*(FreeCAD.Vector(*focus) - d * 500.0)))
    cam.focalDistance.setValue(500.0)
    cam.height.setValue(height)


def run_unattended(main):
    """Run main() and quit FreeCAD whatever happens: these scripts run unattended under xvfb-run."""
    try:
        main()
    except Exception:  # noqa: BLE001  -- report, then quit anyway
        traceback.print_exc()
    finally:
        os._exit(0)


def rest_and_band(base, mesh):
    """Two Mesh.Mesh of a rounded `mesh`: the facets that keep a vertex of `base` (the sharp input), and
    the facets whose three vertices are all new (the round and its band).  Input vertices keep their
    exact values, so "new" is exact."""
    old = {tuple(p) for p in base.Topology[0]}
    points, facets = mesh.Topology
    is_new = np.array([tuple(p) not in old for p in points])
    band = is_new[np.asarray(facets)].all(axis=1)
    parts = []
    for keep in (~band, band):
        part = Mesh.Mesh(mesh)
        part.removeFacets([int(i) for i in np.flatnonzero(~keep)])
        parts.append(part)
    return parts
