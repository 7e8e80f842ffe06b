#!/usr/bin/python3
"""Writes scenes/data/plate_hole.vtu: Kirsch's displacement field around a circular hole, sampled
at the nodes of a quadrilateral mesh, the finite-element-like input of scenes/plate_hole.lua.

Kirsch's solution (plane stress; an infinite plate with a hole of radius a under a uniaxial stress
sigma along x at infinity), in polar coordinates (r, theta) about the hole's centre, with shear
modulus mu = E / (2 (1 + nu)) and kappa = (3 - nu) / (1 + nu):
  u_x = sigma a / (8 mu) [ (r/a)(kappa + 1) cos t + 2 (a/r)((1 + kappa) cos t + cos 3t) - 2 (a/r)^3 cos 3t ]
  u_y = sigma a / (8 mu) [ (r/a)(kappa - 3) sin t + 2 (a/r)((1 - kappa) sin t + sin 3t) - 2 (a/r)^3 sin 3t ]
Far from the hole this is the uniform strain u_x = sigma x / E, u_y = -nu sigma y / E.

The mesh is in millimetres (the scene reads it with scale = 1e-3): a ring from the hole (r = a)
to r = outer, n_theta cells around and n_r cells across, radially graded (geometric) where the
field varies fastest. Values are the closed form at the nodes, in float64; between nodes the field
is the mesh's bilinear interpolation, as an FE solution on this mesh would be.

Run:  /usr/bin/python3 scripts/make_kirsch_field.py [output.vtu]   (Debian's python3-vtk9)
"""
import math
import sys

import vtk

A_MM = 5.0          # hole radius
OUTER_MM = 30.0     # mesh's outer radius (the scene renders the ring up to 25 mm)
N_THETA = 128
N_R = 32
E_PA = 70e9         # aluminium
NU = 0.33
SIGMA_PA = 70e6     # far-field stress along x: sigma / E = 1e-3


def kirsch(x, y):
    r = math.hypot(x, y)
    t = math.atan2(y, x)
    mu = E_PA / (2 * (1 + NU))
    kappa = (3 - NU) / (1 + NU)
    c = SIGMA_PA * A_MM / (8 * mu)
    q = A_MM / r
    ux = c * ((r / A_MM) * (kappa + 1) * math.cos(t) + 2 * q * ((1 + kappa) * math.cos(t) + math.cos(3 * t))
              - 2 * q ** 3 * math.cos(3 * t))
    uy = c * ((r / A_MM) * (kappa - 3) * math.sin(t) + 2 * q * ((1 - kappa) * math.sin(t) + math.sin(3 * t))
              - 2 * q ** 3 * math.sin(3 * t))
    return ux, uy


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/data/plate_hole.vtu"
    points = vtk.vtkPoints()
    points.SetDataTypeToDouble()
    disp = vtk.vtkDoubleArray()
    disp.SetName("displacement")
    disp.SetNumberOfComponents(3)
    for i in range(N_R + 1):
        r = A_MM * (OUTER_MM / A_MM) ** (i / N_R)
        for j in range(N_THETA):
            t = 2 * math.pi * j / N_THETA
            x, y = r * math.cos(t), r * math.sin(t)
            points.InsertNextPoint(x, y, 0.0)
            ux, uy = kirsch(x, y)
            disp.InsertNextTuple3(ux, uy, 0.0)
    grid = vtk.vtkUnstructuredGrid()
    grid.SetPoints(points)
    for i in range(N_R):
        for j in range(N_THETA):
            k = (j + 1) % N_THETA
            quad = vtk.vtkQuad()
            ids = quad.GetPointIds()
            ids.SetId(0, i * N_THETA + j)
            ids.SetId(1, (i + 1) * N_THETA + j)
            ids.SetId(2, (i + 1) * N_THETA + k)
            ids.SetId(3, i * N_THETA + k)
            grid.InsertNextCell(quad.GetCellType(), ids)
    grid.GetPointData().AddArray(disp)
    writer = vtk.vtkXMLUnstructuredGridWriter()
    writer.SetFileName(out)
    writer.SetInputData(grid)
    writer.SetDataModeToAppended()
    writer.EncodeAppendedDataOff()
    writer.SetCompressorTypeToZLib()
    if not writer.Write():
        sys.exit("cannot write " + out)
    print(f"{out}: {grid.GetNumberOfPoints()} points, {grid.GetNumberOfCells()} quads, "
          f"hole radius {A_MM} mm, outer radius {OUTER_MM} mm, sigma/E = {SIGMA_PA / E_PA:g}")


if __name__ == "__main__":
    main()
