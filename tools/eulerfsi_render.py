"""A 3-D picture of a run in the manner of Alghalibi, Rosti & Brandt (2019), Fig. 1: the particle's
psi = 1/2 surface at several times in the (transparent) pipe, coloured by the speed |u| or by the
elastic energy density psi G (tr B det(B)^(-1/3) - 3) / 2 (`--color energy`, how strained it is).

Runs inside ParaView's own Python, from the run's fields.xdmf (XDMF reader), so it is also the
proof that ParaView opens our files:

    pvbatch tools/eulerfsi_render.py RUN_DIR --out picture.png [--times 0 20 40] [--size 2400 500]

With no X display, start one: `tools/render_3d.sh RUN_DIR picture.png` wraps this in xvfb-run.
Each snapshot's surface keeps its radial position (y, z) and is moved along x to its own slot,
`--spacing` apart (2.5 pipe diameters by default): the particle travels tens to hundreds of
diameters, which at actual scale would leave a hair-thin picture.
"""
import argparse
import os
import sys

from paraview import simple as pv


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("run", help="run directory holding fields.xdmf")
    p.add_argument("--out", required=True, help="PNG to write")
    p.add_argument("--times", type=float, nargs="*", default=None,
                   help="snapshot times to show (nearest written one each); default: up to 6 spread evenly")
    p.add_argument("--size", type=int, nargs=2, default=[2400, 500], help="image width and height in pixels")
    p.add_argument("--pipe-radius", type=float, default=0.5, help="radius of the drawn pipe (domain units)")
    p.add_argument("--spacing", type=float, default=2.5, help="distance along x between the snapshots")
    p.add_argument("--color", choices=["speed", "energy"], default="speed",
                   help="colour the surface by |u| or by the elastic energy density")
    return p.parse_args(argv)


def run_title(run):
    """Re, We, model and resolution from the run's config.resolved.toml (empty if unreadable)."""
    try:
        import tomllib
        with open(os.path.join(run, "config.resolved.toml"), "rb") as f:
            cfg = tomllib.load(f)
        solid = cfg["solid"][0]
        h = cfg["domain"]["length"][1] / cfg["domain"]["cells"][1]
        model = {"paper": "paper model", "reference-map": "reference map"}.get(solid.get("model", "paper"), "?")
        return (f"Re = {cfg['flow']['Re']:g}, We = {solid['We']:g}, mu_s/mu_f = {solid.get('viscosity_ratio', 1):g}: "
                f"{model}, {solid['diameter'] / h:.0f} cells per particle diameter")
    except (ImportError, OSError, KeyError, IndexError, ValueError, ZeroDivisionError):
        return ""


def chosen_times(available, wanted, most=6):
    if not available:
        sys.exit("eulerfsi_render: the run has no field snapshots (set output.fields_every)")
    if wanted:
        return sorted({min(available, key=lambda t: abs(t - w)) for w in wanted})
    if len(available) <= most:
        return list(available)
    step = (len(available) - 1) / (most - 1)
    return [available[round(i * step)] for i in range(most)]


def main(argv):
    args = parse_args(argv)
    xdmf = os.path.join(args.run, "fields.xdmf")
    if not os.path.isfile(xdmf):
        sys.exit(f"eulerfsi_render: {xdmf} not found (a run writes it when output.fields_every > 0)")
    reader = pv.XDMFReader(FileNames=[xdmf])
    if args.color == "energy" and "elastic_energy" not in reader.CellArrayStatus.Available:
        sys.exit("eulerfsi_render: this run's snapshots have no elastic_energy field: use --color speed")
    reader.CellArrayStatus = ["psi", "velocity"] + (["elastic_energy"] if args.color == "energy" else [])
    times = chosen_times(list(reader.TimestepValues), args.times)
    view = pv.CreateView("RenderView")
    pv.SetActiveView(view)
    view.ViewSize = args.size
    if hasattr(view, "UseColorPaletteForBackground"):  # ParaView >= 5.10 takes the palette's otherwise
        view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    view.OrientationAxesVisibility = 0
    lut = pv.GetColorTransferFunction("speed")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    shown_count, top_speed = 0, 0.0
    for t in times:
        frozen = pv.ForceTime(Input=reader, ForcedTime=t)
        points = pv.CellDatatoPointData(Input=frozen)
        speed = pv.Calculator(Input=points, ResultArrayName="speed",
                              Function="mag(velocity)" if args.color == "speed" else "elastic_energy")
        surface = pv.Contour(Input=speed, ContourBy=["POINTS", "psi"], Isosurfaces=[0.5], ComputeScalars=1)
        surface.UpdatePipeline(t)
        info = surface.GetDataInformation()
        if info.GetNumberOfPoints() == 0:
            print(f"eulerfsi_render: no psi = 1/2 surface at t = {t:g}, skipped")
            continue
        bounds = info.GetBounds()
        slot = shown_count * args.spacing
        moved = pv.Transform(Input=surface)
        moved.Transform.Translate = [slot - 0.5 * (bounds[0] + bounds[1]), 0.0, 0.0]
        top_speed = max(top_speed, surface.PointData["speed"].GetRange()[1])
        shown = pv.Show(moved, view)
        pv.ColorBy(shown, ("POINTS", "speed"))
        shown.LookupTable = lut
        label = pv.Text(Text=f"t = {t:.3g}")
        shown_label = pv.Show(label, view, "TextSourceRepresentation")
        shown_label.TextPropMode = "Billboard 3D Text"
        shown_label.BillboardPosition = [slot, 0.0, -1.1 * args.pipe_radius]
        shown_label.Color = [0.0, 0.0, 0.0]
        shown_label.FontSize = 14
        shown_count += 1
    if shown_count == 0:
        sys.exit("eulerfsi_render: no particle surface in any chosen snapshot")
    x_lo, x_hi = 0.0, (shown_count - 1) * args.spacing
    lut.RescaleTransferFunction(0.0, max(top_speed, 1e-12))
    # the pipe: a cylinder along x (VTK's runs along y), drawn faint so the particles show through
    margin = 0.5 * args.spacing
    pipe = pv.Cylinder(Radius=args.pipe_radius, Height=x_hi - x_lo + 2 * margin, Resolution=96, Capping=0)
    placed = pv.Transform(Input=pipe)
    placed.Transform.Rotate = [0.0, 0.0, 90.0]
    placed.Transform.Translate = [0.5 * (x_lo + x_hi), 0.0, 0.0]
    wall = pv.Show(placed, view)
    wall.Opacity = 0.15
    wall.AmbientColor = wall.DiffuseColor = [0.4, 0.4, 0.5]
    title = run_title(args.run)
    if title:
        text = pv.Show(pv.Text(Text=title), view)
        text.WindowLocation = "Upper Center"
        text.Color = [0.0, 0.0, 0.0]
        text.FontSize = 16
    bar = pv.GetScalarBar(lut, view)
    bar.Title = "|u| / U_b" if args.color == "speed" else "elastic energy / (rho U_b^2)"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
    bar.Visibility = 1
    # side view across the flow, slightly from above, the whole travelled length in the frame
    view.CameraPosition = [0.5 * (x_lo + x_hi), -3.0 * (x_hi - x_lo + 2), 1.0 * (x_hi - x_lo + 2)]
    view.CameraFocalPoint = [0.5 * (x_lo + x_hi), 0.0, 0.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.ResetCamera()
    # ResetCamera fits the bounding sphere into the height; the pipe is long: fill the width instead
    pv.GetActiveCamera().Zoom(0.85 * args.size[0] / args.size[1])
    pv.SaveScreenshot(args.out, view, ImageResolution=args.size)
    print(f"eulerfsi_render: {shown_count} snapshots (t = {', '.join(f'{t:g}' for t in times)}) -> {args.out}")


if __name__ == "__main__":
    main(sys.argv[1:])
