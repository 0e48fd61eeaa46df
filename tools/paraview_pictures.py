"""A picture of a run's last frame, rendered by ParaView from its XDMF sidecar through the default Xdmf3 reader.
Usage (no screen needed): xvfb-run -a pvbatch tools/paraview_pictures.py OUT.xdmf PICTURE.png KIND
KIND: particles (the bodies as discs or spheres of their radius, coloured by velocity along x), or damage (a rigid-cell
run: the cells' outlines, the facets with damage above 0.01 coloured by it)."""
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, Render, SaveScreenshot, Show,
                             Threshold, Xdmf3ReaderS)

xdmf, png, kind = sys.argv[1], sys.argv[2], sys.argv[3]
reader = Xdmf3ReaderS(FileName=[xdmf])
view = GetActiveViewOrCreate("RenderView")
view.ViewTime = reader.TimestepValues[-1]
size = [1400, 700] if kind == "particles" else [1000, 900]
view.ViewSize = size
if kind == "particles":
    shown = Show(reader, view)
    shown.SetRepresentationType("Point Gaussian")
    shown.ScaleByArray = 1
    shown.SetScaleArray = ["POINTS", "radius"]
    shown.UseScaleFunction = 0
    shown.GaussianRadius = 1
    ColorBy(shown, ("POINTS", "velocity", "X"))
    shown.RescaleTransferFunctionToDataRange(True, False)
else:
    outline = Show(reader, view)
    outline.SetRepresentationType("Wireframe")
    outline.ColorArrayName = ["POINTS", ""]
    outline.AmbientColor = outline.DiffuseColor = [0.7, 0.7, 0.7]
    shown = Show(Threshold(Input=reader, Scalars=["CELLS", "damage"], LowerThreshold=0.01, UpperThreshold=1.0), view)
    shown.LineWidth = 4
    ColorBy(shown, ("CELLS", "damage"))
    lut = GetColorTransferFunction("damage")
    lut.ApplyPreset("Inferno (matplotlib)", True)
    lut.RescaleTransferFunction(0.0, 1.0)
shown.SetScalarBarVisibility(view, True)
view.ResetCamera()
Render()
SaveScreenshot(png, view, ImageResolution=size)
