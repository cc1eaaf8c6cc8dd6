"""Shared by the rendering scripts: read placed blocks from a VTU written by tessera, and colour them
(fixed blocks grey, free blocks orange, shaded by face orientation)."""
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader


def load_blocks(path):
    """Triangles (T x 3 x 3, in mm) and the fixed flag of each, from a blocks VTU."""
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid.GetNumberOfCells() == 0:
        raise SystemExit(f"{path}: no cells; export a bundle with bodies (tessera tile ...)")
    points = vtk_to_numpy(grid.GetPoints().GetData()) * 1e3
    cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 3)
    fixed = vtk_to_numpy(grid.GetCellData().GetArray("fixed"))
    return points[cells], fixed


def block_colours(triangles, fixed, towards):
    """RGB per triangle: grey (fixed) or orange (free), brighter the more a face turns to `towards`."""
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    towards = np.asarray(towards, dtype=float) / np.linalg.norm(towards)
    shade = 0.45 + 0.55 * np.abs(normals @ towards)
    base = np.where(fixed[:, None] == 1, np.array([0.62, 0.64, 0.68]), np.array([0.95, 0.55, 0.15]))
    return np.clip(base * shade[:, None], 0, 1)
