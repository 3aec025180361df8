#!/usr/bin/python3
"""Render a PNG snapshot of a tissuefem run from its VTU output.

usage: render_snapshot.py RUN_DIR|FILE.pvd|FILE.pvtu|FILE.vtu OUT.png
         [--field NAME] [--step last|N] [--size WxH] [--view xy|iso]
         [--up x|y|z]
The body warped by 'displacement', coloured by --field (von Mises stress by
default; vectors by magnitude), over its undeformed outline. A directory or
.pvd gives its last step, or step N (solution-NNNNN) with --step N. Planar
meshes are seen from +z (xy), 3D ones from a corner (iso) with --up upwards.
Exit status 2: bad input; 1: other errors. Needs python3-vtk9, and without
a display xvfb (Debian's VTK renders through X only).
"""
import argparse
import math
import os
import re
import shutil
import signal
import sys
import xml.etree.ElementTree as ET


def fail(msg, status=2):
    sys.stderr.write('render_snapshot: error: %s\n' % msg)
    sys.exit(status)


try:
    import vtk
except ImportError:  # a pyenv/venv python3 does not see Debian's python3-vtk9
    if (os.path.exists('/usr/bin/python3') and not os.environ.get('RS_PY')
            and sys.executable != '/usr/bin/python3'):
        os.environ['RS_PY'] = '1'
        os.execv('/usr/bin/python3', ['/usr/bin/python3'] + sys.argv)
    fail('no VTK for Python (apt-get install python3-vtk9)', 1)
vtk.vtkObject.GlobalWarningDisplayOff()  # errors are reported by fail()


def vset(obj, **settings):
    """vset(x, Color=(r, g, b), ModeTo='Fast') calls x.SetColor(r, g, b),
    x.SetModeToFast() and returns x."""
    for name, value in settings.items():
        if name.endswith('To'):
            getattr(obj, 'Set' + name + value)()
        else:
            getattr(obj, 'Set' + name)(*(value if isinstance(value, tuple)
                                         else (value,)))
    return obj


class Parser(argparse.ArgumentParser):
    def error(self, message):  # one line on stderr, not a usage block
        fail(message)


def parse_args():
    def size(s):  # argparse names the function in its message
        m = re.fullmatch(r'(\d{2,4})x(\d{2,4})', s)
        if not m:
            raise ValueError(s)
        return int(m[1]), int(m[2])

    def step(s):  # int(): '007' is step 7
        return s if s == 'last' else str(int(s))

    p = Parser(prog='render_snapshot', description=__doc__.split('\n')[0])
    p.add_argument('input')
    p.add_argument('output')
    p.add_argument('--field', default='von_Mises_Cauchy_stress')
    p.add_argument('--step', default='last', type=step)
    p.add_argument('--size', default='800x600', type=size)
    p.add_argument('--view', choices=('xy', 'iso'))
    p.add_argument('--up', choices=('x', 'y', 'z'), default='z')
    a = p.parse_args()
    if not os.path.isdir(os.path.dirname(os.path.abspath(a.output))):
        fail('no directory for %s' % a.output)
    return a


def step_of(path, default):
    # tissuefem writes solution-NNNNN.pvtu (pieces .P.vtu); NNNNN is the step
    m = re.search(r'(\d+)(\.\d+)?\.p?vtu$', path)
    return int(m[1]) if m else default


def list_steps(path):
    """[(step, time or None, file)] in output order."""
    if os.path.isdir(path):  # tissuefem's output directory
        path = os.path.join(path, 'solution.pvd')
    if not os.path.isfile(path):
        fail('no such file: %s' % path)
    if re.search(r'\.p?vtu$', path):
        return [(step_of(path, 0), None, path)]
    if not path.endswith('.pvd'):
        fail('%s is not a directory, .pvd, .pvtu or .vtu' % path)
    try:
        sets = [(float(d.get('timestep', 'nan')), d.get('file', ''))
                for d in ET.parse(path).getroot().iter('DataSet')]
    except (ET.ParseError, ValueError) as e:
        fail('cannot read %s: %s' % (path, e))
    if not sets:
        fail('%s lists no data sets' % path)
    return [(step_of(f, i), t, os.path.join(os.path.dirname(path), f))
            for i, (t, f) in enumerate(sets)]


def read_grid(path):
    reader = (vtk.vtkXMLPUnstructuredGridReader() if path.endswith('.pvtu')
              else vtk.vtkXMLUnstructuredGridReader())
    errors = []  # VTK readers report through events, not exceptions
    reader.AddObserver('ErrorEvent', lambda *a: errors.append(a))
    reader.SetFileName(path)
    reader.Update()
    if errors or reader.GetOutput().GetNumberOfCells() == 0:
        fail('cannot read %s (damaged, a piece missing, or no cells)' % path)
    return reader.GetOutput()


def colour_range(arr):
    """(lo, hi, min, max): clipped to the 0.5 and 99.5 % quantiles only when
    the values beyond them (a grasped node, a singular corner) would squeeze
    the rest into a quarter of the colours."""
    one = arr.GetNumberOfComponents() == 1  # else colour by the magnitude
    v = sorted(x for x in (arr.GetTuple1(i) if one else
                           math.hypot(*arr.GetTuple(i))
                           for i in range(arr.GetNumberOfTuples()))
               if math.isfinite(x))
    if not v:
        fail('%s has no finite values' % arr.GetName())
    plo, phi = v[(len(v) - 1) // 200], v[(len(v) - 1) * 199 // 200]
    lo = plo if plo - v[0] > 0.25 * (phi - plo) else v[0]
    hi = phi if v[-1] - phi > 0.25 * (phi - plo) else v[-1]
    pad = 0 if hi > lo else abs(hi) * 1e-6 or 1e-12  # a constant field
    return lo - pad, hi + pad, v[0], v[-1]


def label_format(lo, hi):
    # plain decimals, with just enough places to tell five ticks apart
    if not 1e-3 <= max(abs(lo), abs(hi)) < 1e6:
        return '%.3g'
    return '%%.%df' % min(max(1 - math.floor(math.log10((hi - lo) / 4)), 0), 6)


def viridis(lo, hi):
    ctf = vset(vtk.vtkColorTransferFunction(), VectorModeTo='Magnitude')
    for x, r, g, b in ((0, .267, .005, .329), (.25, .229, .322, .546),
                       (.5, .128, .567, .551), (.75, .369, .789, .383),
                       (1, .993, .906, .144)):
        ctf.AddRGBPoint(lo + x * (hi - lo), r, g, b)
    return ctf


def rerun_under_xvfb(size):
    # Debian's VTK has only the GLX render window (no EGL, no OSMesa), so it
    # needs an X server: Xvfb is one in memory, drawing with Mesa's llvmpipe.
    if os.environ.get('RS_XVFB'):
        fail('still no X display under xvfb-run', 1)
    if not shutil.which('xvfb-run'):
        fail('no X display, and VTK needs one: apt-get install xvfb xauth', 1)
    os.environ['RS_XVFB'] = '1'
    os.execvp('xvfb-run', ['xvfb-run', '-a', '-s', '-screen 0 %dx%dx24' % size,
                           sys.executable, os.path.abspath(__file__)] +
              sys.argv[1:])


def outline(grid, planar, towards, lift):
    # deal.II gives every cell its own vertices: merge them, so that the
    # surface filter sees shared faces and keeps only the outer ones.
    merged, merge = vtk.vtkUnstructuredGrid(), vtk.vtkMergeCells()
    vset(merge, UnstructuredGrid=merged, TotalNumberOfDataSets=1,
         TotalNumberOfPoints=grid.GetNumberOfPoints(),
         TotalNumberOfCells=grid.GetNumberOfCells())
    merge.MergeDataSet(grid)
    merge.Finish()
    edges = surf = vset(vtk.vtkDataSetSurfaceFilter(), InputData=merged)
    surf.Update()
    if planar and surf.GetOutput().GetNumberOfPolys():  # the boundary curve
        edges = vset(vtk.vtkFeatureEdges(), FeatureEdges=0, ManifoldEdges=0,
                     NonManifoldEdges=0)
    elif not planar:  # the contour seen from the camera, and sharp edges
        edges = vset(vtk.vtkPolyDataSilhouette(), Vector=tuple(towards),
                     DirectionTo='SpecifiedVector', EnableFeatureAngle=1,
                     FeatureAngle=50, BorderEdges=1)
    if edges is not surf:  # else 1D: the bar itself
        vset(edges, InputData=surf.GetOutput()).Update()
    # data, not a pipeline: Python frees the filters when this returns
    mapper = vset(vtk.vtkDataSetMapper(), ScalarVisibility=0,
                  InputData=edges.GetOutput())
    actor = vset(vtk.vtkActor(), Mapper=mapper)
    if planar:  # off the body's plane, towards the viewer
        actor.SetPosition(*[lift * c for c in towards])
    vset(actor.GetProperty(), Color=(.35, .35, .35), Opacity=0.6,
         LineWidth=1.5, Lighting=0)
    return actor


def write_png(win, path):
    # Written beside the target and renamed: OUT.png is never half written.
    out = os.path.abspath(path)
    tmp = '%s/.%s.%d.png' % (os.path.dirname(out), os.path.basename(out),
                             os.getpid())
    grab = vset(vtk.vtkWindowToImageFilter(), Input=win, ReadFrontBuffer=0)
    writer = vset(vtk.vtkPNGWriter(), CompressionLevel=9, FileName=tmp)
    writer.SetInputConnection(grab.GetOutputPort())
    try:
        writer.Write()
        if writer.GetErrorCode() or not os.path.getsize(tmp):
            fail('could not write %s' % path, 1)
        os.replace(tmp, out)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def main():
    args = parse_args()
    steps = list_steps(args.input)
    chosen = [s for s in steps if args.step in ('last', str(s[0]))]
    if not chosen:
        fail('no step %s; there are %s' % (args.step, ', '.join(
            str(s[0]) for s in steps)))
    step, time, path = chosen[-1]
    grid = read_grid(path)
    points, cells = grid.GetPointData(), grid.GetCellData()
    if points.GetArray('displacement') is None:
        fail('%s has no point field displacement' % path)
    arr = points.GetArray(args.field) or cells.GetArray(args.field)
    if arr is None:
        fail('no field %r in %s; it has %s' % (args.field, path, ', '.join(
            d.GetArrayName(i) for d in (points, cells)
            for i in range(d.GetNumberOfArrays()))))
    lo, hi, vmin, vmax = colour_range(arr)
    if (vtk.vtkRenderWindow().GetClassName() == 'vtkXOpenGLRenderWindow'
            and not os.environ.get('DISPLAY')):
        rerun_under_xvfb(args.size)  # the input is fine: now the picture

    warp = vset(vtk.vtkWarpVector(), InputData=grid, InputArrayToProcess=(
        0, 0, 0, 0, 'displacement'))  # the 4th 0: a point field
    warp.Update()
    deformed = warp.GetOutput()
    # Cells keep their own vertices, so a field with one value per cell (J,
    # stress) comes out flat per cell and a nodal one (velocity) smooth.
    colours = viridis(lo, hi)
    mapper = vset(vtk.vtkDataSetMapper(), InputData=deformed,
                  LookupTable=colours, UseLookupTableScalarRange=1,
                  ScalarModeTo='UsePointFieldData' if points.GetArray(
                      args.field) else 'UseCellFieldData')
    mapper.SelectColorArray(args.field)
    mapper.SetResolveCoincidentTopologyToPolygonOffset()  # outline in front
    body = vset(vtk.vtkActor(), Mapper=mapper)
    vset(body.GetProperty(), Ambient=0.35, Diffuse=0.7,  # colours as the bar
         LineWidth=4)  # for 1D bars

    b0, b1 = grid.GetBounds(), deformed.GetBounds()
    planar = b0[4] == b0[5] == b1[4] == b1[5]
    if (args.view or ('xy' if planar else 'iso')) == 'xy':
        towards, up = (0, 0, 1), (0, 1, 0)
    else:  # from up + right + towards the viewer (right-handed)
        towards = {'z': (1, -1, 1), 'y': (1, 1, 1), 'x': (1, 1, -1)}[args.up]
        up = tuple(float(args.up == a) for a in 'xyz')

    # Three bands, so that neither text nor colour bar covers the body.
    (w, h), top, bottom = args.size, 0.07, 0.17
    win = vset(vtk.vtkRenderWindow(), OffScreenRendering=1, Size=(w, h))
    text_ren, ren, bar_ren = (
        vset(vtk.vtkRenderer(), Viewport=v, Background=(1, 1, 1))
        for v in ((0, 1 - top, 1, 1), (0, bottom, 1, 1 - top),
                  (0, 0, 1, bottom)))
    for r in (text_ren, ren, bar_ren):
        win.AddRenderer(r)
    size = math.dist(b0[0::2], b0[1::2]) or 1.0
    ren.AddActor(body)
    ren.AddActor(outline(grid, planar, towards, 1e-3 * size))
    vset(ren.GetActiveCamera(), FocalPoint=(0, 0, 0), Position=towards,
         ViewUp=up, ParallelProjection=1)
    ren.ResetCameraScreenSpace()  # zoomed to the bounding box on screen

    fs = max(10, round(h / 34))
    run = os.path.basename(os.path.dirname(os.path.abspath(path)))
    notes = [('%s   step %d%s' % (run, step, '' if time is None else
                                  '   t = %g' % time), fs, 0.02, 'Left')]
    if lo > vmin or hi < vmax:  # the bar does not show every value
        fmt = label_format(vmin, vmax)
        notes.append(('colours clipped; values %s to %s' % (
            fmt % vmin, fmt % vmax), fs - 2, 0.98, 'Right'))
    for words, font, x, justify in notes:
        t = vset(vtk.vtkTextActor(), Input=words, Position=(x, 0.5))
        t.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
        vset(t.GetTextProperty(), FontSize=font, Color=(.1, .1, .1),
             JustificationTo=justify, VerticalJustificationTo='Centered')
        text_ren.AddActor2D(t)
    bar = vset(vtk.vtkScalarBarActor(), LookupTable=colours,
               OrientationTo='Horizontal',
               Title=args.field if arr.GetNumberOfComponents() == 1 else
               '|%s|' % args.field, NumberOfLabels=5, BarRatio=0.25,
               LabelFormat=label_format(lo, hi), Position=(0.15, 0.08),
               Width=0.7, Height=0.9, TextPositionTo='PrecedeScalarBar',
               UnconstrainedFontSize=1)  # the sizes below, not fitted
    for prop, pt in ((bar.GetTitleTextProperty(), fs),
                     (bar.GetLabelTextProperty(), fs - 2)):
        vset(prop, Color=(.1, .1, .1), FontSize=pt, Italic=0, Shadow=0,
             Bold=0)
    bar_ren.AddActor2D(bar)
    win.Render()
    write_png(win, args.output)


if __name__ == '__main__':
    # SIGTERM as an exception, so that the temporary PNG is removed
    signal.signal(signal.SIGTERM, lambda *a: sys.exit(143))
    main()
