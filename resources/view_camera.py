"""The camera both pictures use: orthographic, looking along a direction with z up on screen."""
import FreeCAD
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
