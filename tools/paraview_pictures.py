"""A picture of a run's last frame, rendered by ParaView from its XDMF sidecar through the default Xdmf3 reader.
Usage (no screen needed): xvfb-run -a pvbatch tools/paraview_pictures.py OUT.xdmf PICTURE.png KIND
KIND: particles (the bodies as discs or spheres of their radius, coloured by velocity along x, and where the frames
record contacts, the force chains: each contact carrying more than a tenth of the largest compression a tube between
the centres, black, wider the larger its normal force), or damage (a rigid-cell run: the cells' outlines, the facets
with damage above 0.01 coloured by it)."""
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, Render, SaveScreenshot, Show,
                             Threshold, Tube, CellDatatoPointData, ExtractSurface, Xdmf3ReaderS)

xdmf, png, kind = sys.argv[1], sys.argv[2], sys.argv[3]
reader = Xdmf3ReaderS(FileName=[xdmf])
view = GetActiveViewOrCreate("RenderView")
view.ViewTime = reader.TimestepValues[-1]
size = [1400, 700] if kind == "particles" else [1000, 900]
view.ViewSize = size
if kind == "particles":
    # The particles and the contacts are two pieces of one block; each has arrays the other lacks, so a threshold
    # on one of them keeps its own piece.
    particles = Threshold(Input=reader, Scalars=["POINTS", "radius"], LowerThreshold=0.0, UpperThreshold=1e30)
    shown = Show(particles, view)
    shown.SetRepresentationType("Point Gaussian")
    shown.ScaleByArray = 1
    shown.SetScaleArray = ["POINTS", "radius"]
    shown.UseScaleFunction = 0
    shown.GaussianRadius = 1
    ColorBy(shown, ("POINTS", "velocity", "X"))
    shown.RescaleTransferFunctionToDataRange(True, False)
    reader.UpdatePipeline(reader.TimestepValues[-1])
    if "normal_force" in reader.CellData.keys():
        # The chains: contacts carrying more than a tenth of the largest compression (the rest would hide the
        # particles).
        largest = reader.CellData["normal_force"].GetRange()[1]
        compressed = Threshold(Input=reader, Scalars=["CELLS", "normal_force"], LowerThreshold=0.1 * largest,
                               UpperThreshold=1e30)
        # A tube filter takes polygonal data: the lines' surface, their forces carried to their ends.
        chains = Tube(Input=ExtractSurface(Input=CellDatatoPointData(Input=compressed)),
                      Scalars=["POINTS", "normal_force"], VaryRadius="By Scalar", NumberofSides=6)
        bounds = reader.GetDataInformation().GetBounds()
        chains.Radius = 0.0004 * max(bounds[1] - bounds[0], bounds[3] - bounds[2])
        chains.RadiusFactor = 10.0
        lines = Show(chains, view)
        lines.ColorArrayName = ["POINTS", ""]
        lines.AmbientColor = lines.DiffuseColor = [0.05, 0.05, 0.05]
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
if kind == "particles":
    view.CameraParallelScale = 0.3 * (view.CameraParallelScale or 1.0)
    view.GetActiveCamera().Zoom(1.8)  # the specimen across the picture
    Render()
SaveScreenshot(png, view, ImageResolution=size)
