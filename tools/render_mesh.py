#!/usr/bin/env python3
"""Render frames of a mesh dump (dump nosb/mesh: .vtp, .vtu, .obj, or a .pvd series) as shaded
surfaces: one picture, or an animated GIF of the frames.

    python3 tools/render_mesh.py frames/cloth.300.vtp -o cloth.png
    python3 tools/render_mesh.py frames/cloth.300.vtp --field c_s[4] --label "von Mises (Pa)"
    python3 tools/render_mesh.py frames/cloth.300.obj --elev 20 --azim -60 --zoom 1.3
    python3 tools/render_mesh.py frames/cloth.pvd -o cloth.gif --title "t = {time:.2f} s"
    python3 tools/render_mesh.py frames/b.50.vtp --mesh-colors gray "#c03030" --stack

Every triangle is one flat polygon (matplotlib's Poly3DCollection, drawn back to front) whose
colour is the base colour, or the colour map's colour of the field averaged over its three
vertices, times Lambert shading: ambient + (1 - ambient) |n . l| with n the triangle's unit
normal and l the light direction (both sides of a cloth lit alike). The light is given in the
camera's frame (right, up, towards the viewer), so it stays where it is when the camera moves.
The base colour is --color, or per mesh (the dump's cell array 'mesh', the OBJ's 'o mesh_K'
objects) --mesh-colors; with --back-color the triangles whose side away from their normal faces
the camera take that colour instead (the two sides of a cloth). The solid boxes of --box (a
table) are drawn first, without their triangles that face away from the camera, and the meshes
over them; with --stack the meshes one after the other in the order of their ids (a ball read
first, then cloths stacked on it from the bottom up), each sorted back to front by itself. One
back-to-front order of all triangles leaves speckles where a cloth lies on a box or another
cloth (triangles of nearly the same depth); drawing in layers leaves none, and is right where
no part of a later layer is behind an earlier one, as for stacked cloths and a table seen from
above. Each polygon's edge is
drawn in its own colour and without antialiasing: neither the background nor blended edges show
along the seams between triangles (no moire on flat regions).

Pictures are W x H inches at --dpi exactly (the defaults 8 x 6 at 100: 800 x 600 pixels). With
several frames (several files, or a .pvd series: its frames in its order) and an output ending
in .gif, every frame is drawn in the same view (the box holding all frames, or --limits) and
written as one frame of the GIF (with Pillow, matplotlib's own dependency; no ffmpeg). The title may name the
frame's time ({time}, from the VTK files' TimeValue) and its step ({step}, the last number of
the file name). Needs numpy and matplotlib only (the files are read here: the ASCII VTK XML that
dump nosb/mesh writes, and OBJ v, o and f lines).
"""
import argparse
import re
import sys
import xml.etree.ElementTree as ET
from collections import namedtuple
from pathlib import Path

import numpy as np

# points (n x 3), triangles (m x 3, 0-based), point arrays {name: values}, the mesh id of each
# triangle (m), the simulation time (None when the file does not say) and the file's step
Frame = namedtuple("Frame", "points triangles fields meshes time step")


def frame_step(path):
    """The last number in the file's name (dump nosb/mesh's timestep), or None."""
    numbers = re.findall(r"\d+", Path(path).name)
    return int(numbers[-1]) if numbers else None


def read_vtk(path):
    """A Frame of an ASCII .vtp or .vtu file."""
    root = ET.parse(path).getroot()
    grid = root.find(str(root.get("type")))
    piece = grid.find("Piece") if grid is not None else None
    if piece is None:
        raise ValueError(f"{path}: no {root.get('type')} piece")

    def values(node):
        if node.get("format", "ascii") != "ascii":
            raise ValueError(f"{path}: only ASCII arrays are read")
        return np.array((node.text or "").split(), dtype=float)

    points = values(piece.find("Points/DataArray")).reshape(-1, 3)
    cells = piece.find("Polys") if piece.find("Polys") is not None else piece.find("Cells")
    arrays = {a.get("Name"): values(a) for a in cells}
    offsets = arrays["offsets"].astype(int)
    if np.any(np.diff(np.concatenate([[0], offsets])) != 3):
        raise ValueError(f"{path}: cells other than triangles")
    triangles = arrays["connectivity"].astype(int).reshape(-1, 3)
    data = piece.find("PointData")
    fields = {a.get("Name"): values(a) for a in data} if data is not None else {}
    meshes = np.ones(len(triangles), int)
    for a in piece.findall("CellData/DataArray"):
        if a.get("Name") == "mesh":
            meshes = values(a).astype(int)
    time = None
    for a in grid.findall("FieldData/DataArray"):
        if a.get("Name") == "TimeValue":
            time = float(values(a)[0])
    return Frame(points, triangles, fields, meshes, time, frame_step(path))


def read_obj(path):
    """A Frame of an OBJ file: polygons split into fans; the mesh id of an 'o mesh_K' object is
    K, of any other object its number in the file (from 1); no fields, no time."""
    points, triangles, meshes = [], [], []
    mesh, objects = 1, 0
    for line in Path(path).read_text().splitlines():
        words = line.split()
        if not words:
            continue
        if words[0] == "v":
            points.append([float(w) for w in words[1:4]])
        elif words[0] == "o":
            objects += 1
            m = re.fullmatch(r"mesh_(\d+)", words[1]) if len(words) > 1 else None
            mesh = int(m.group(1)) if m else objects
        elif words[0] == "f":
            idx = [int(w.split("/")[0]) for w in words[1:]]
            idx = [i - 1 if i > 0 else len(points) + i for i in idx]
            triangles += [[idx[0], idx[k], idx[k + 1]] for k in range(1, len(idx) - 1)]
            meshes += [mesh] * (len(idx) - 2)
    return Frame(np.array(points, float), np.array(triangles, int).reshape(-1, 3), {},
                 np.array(meshes, int), None, frame_step(path))


def read_mesh(path):
    suffix = Path(path).suffix
    if suffix in (".vtp", ".vtu"):
        return read_vtk(path)
    if suffix == ".obj":
        return read_obj(path)
    raise ValueError(f"{path}: not a .vtp, .vtu or .obj file")


def series_files(path):
    """The files of a .pvd series in its order, relative to the series file's folder."""
    root = ET.parse(path).getroot()
    files = [Path(path).parent / d.get("file") for d in root.iter("DataSet")]
    if not files:
        raise ValueError(f"{path}: no DataSet in the series")
    return files


def box_mesh(lo, hi):
    """The 8 corners and 12 outward-facing triangles of the box [lo, hi] (3-vectors)."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    points = np.array([[(lo, hi)[(k >> d) & 1][d] for d in range(3)] for k in range(8)])
    # corner k has x = hi when bit 0 is set, y when bit 1, z when bit 2; each face's four
    # corners in order around it, as two triangles turned to face outwards
    faces = [(0, 2, 6, 4), (1, 3, 7, 5), (0, 1, 5, 4), (2, 3, 7, 6), (0, 1, 3, 2), (4, 5, 7, 6)]
    triangles = np.array([t for a, b, c, d in faces for t in ((a, b, c), (a, c, d))])
    inward = np.sum(normals(points, triangles) * (points[triangles].mean(axis=1)
                                                  - (lo + hi) / 2), axis=1) < 0
    triangles[inward] = triangles[inward][:, ::-1]
    return points, triangles


def camera_frame(elev, azim):
    """Unit vectors (right, up, towards the viewer) of matplotlib's camera at elev, azim
    (degrees)."""
    e, a = np.radians(elev), np.radians(azim)
    toward = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    right = np.array([-np.sin(a), np.cos(a), 0.0])
    return right, np.cross(toward, right), toward


def normals(points, triangles):
    """Unit normal of every triangle (zero for a degenerate one)."""
    tri = points[triangles]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(n, axis=1)
    return n / np.where(length > 0, length, 1.0)[:, None]


def lambert(points, triangles, light, ambient):
    """ambient + (1 - ambient) |n . l| per triangle (l a unit vector)."""
    return ambient + (1.0 - ambient) * np.abs(normals(points, triangles) @ light)


class Scene:
    """What stays the same from frame to frame: camera, light, colours, field range, limits."""

    def __init__(self, args, frames):
        from matplotlib import colors as mcolors
        import matplotlib.pyplot as plt

        self.args = args
        self.right, self.up, self.toward = camera_frame(args.elev, args.azim)
        light = args.light[0] * self.right + args.light[1] * self.up + args.light[2] * self.toward
        self.light = light / np.linalg.norm(light)
        self.to_rgb = mcolors.to_rgb
        self.norm = self.cmap = None
        if args.field:
            for f in frames:
                if args.field not in f.fields:
                    raise ValueError(f"no field {args.field} in the file (fields: "
                                     f"{', '.join(f.fields) or 'none'})")
            faces = [f.fields[args.field][f.triangles].mean(axis=1) for f in frames]
            lo, hi = args.range if args.range else (min(v.min() for v in faces),
                                                    max(v.max() for v in faces))
            self.norm = mcolors.Normalize(lo, hi if hi > lo else lo + 1.0)
            self.cmap = plt.get_cmap(args.cmap)
        if args.limits:
            lo, hi = np.array(args.limits[0::2]), np.array(args.limits[1::2])
        else:
            lo = np.min([f.points.min(axis=0) for f in frames], axis=0)
            hi = np.max([f.points.max(axis=0) for f in frames], axis=0)
        # equal scales on the three axes; a flat mesh keeps a thin box (matplotlib needs one)
        self.centre, self.half = (lo + hi) / 2, np.maximum((hi - lo) / 2, 0.05 * max(hi - lo))
        self.boxes = [box_mesh(b[0::2], b[1::2]) for b in args.box or []]

    def shaded(self, base, points, triangles):
        return np.clip(base * lambert(points, triangles, self.light,
                                      self.args.ambient)[:, None], 0.0, 1.0)

    def layers(self, frame):
        """(polygons, shaded RGB) in drawing order: the boxes (their triangles facing away from
        the camera left out), then the frame's triangles, all together or (--stack) mesh by
        mesh."""
        args = self.args
        if self.norm is not None:
            per_face = frame.fields[args.field][frame.triangles].mean(axis=1)
            base = self.cmap(self.norm(per_face))[:, :3]
        else:
            if args.mesh_colors:
                palette = np.array([self.to_rgb(c) for c in args.mesh_colors])
                base = palette[(frame.meshes - 1) % len(palette)]
            else:
                base = np.tile(self.to_rgb(args.color), (len(frame.triangles), 1))
            if args.back_color:
                away = normals(frame.points, frame.triangles) @ self.toward < 0
                base[away] = self.to_rgb(args.back_color)
        rgb = self.shaded(base, frame.points, frame.triangles)
        polygons = frame.points[frame.triangles]
        boxes = [np.zeros((0, 3, 3))], [np.zeros((0, 3))]
        for points, triangles in self.boxes:
            keep = normals(points, triangles) @ self.toward > 0
            colour = np.tile(self.to_rgb(args.box_color), (keep.sum(), 1))
            boxes[0].append(points[triangles[keep]])
            boxes[1].append(self.shaded(colour, points, triangles[keep]))
        layers = [(np.concatenate(boxes[0]), np.concatenate(boxes[1]))]
        if args.stack:
            layers += [(polygons[frame.meshes == m], rgb[frame.meshes == m])
                       for m in np.unique(frame.meshes)]
        else:
            layers.append((polygons, rgb))
        return layers

    def figure(self):
        import matplotlib.pyplot as plt

        args = self.args
        fig = plt.figure(figsize=args.size, dpi=args.dpi, facecolor="white")
        width = 0.86 if self.norm is not None else 1.0
        ax = fig.add_axes([0.0, 0.0, width, 1.0], projection="3d")
        for setter, c, h in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), self.centre, self.half):
            setter(c - h, c + h)
        ax.set_box_aspect(self.half, zoom=args.zoom)
        ax.view_init(elev=args.elev, azim=args.azim)
        ax.set_axis_off()
        ax.computed_zorder = False
        if self.norm is not None:
            bar = fig.add_axes([0.87, 0.2, 0.025, 0.6])
            fig.colorbar(plt.cm.ScalarMappable(norm=self.norm, cmap=self.cmap), cax=bar,
                         label=args.label or args.field)
        return fig, ax

    def draw(self, fig, ax, frame):
        """Replace the polygons and title of (fig, ax) by the frame's."""
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection

        for old in list(ax.collections):
            old.remove()
        # the boxes first, the meshes over them, each layer sorted back to front by itself
        for order, (polygons, rgb) in enumerate(self.layers(frame)):
            if len(polygons):
                ax.add_collection3d(Poly3DCollection(polygons, facecolors=rgb, edgecolors=rgb,
                                                     linewidths=0.3, antialiased=False,
                                                     zorder=order + 1, clip_on=False))
        if self.args.title:
            time = frame.time if frame.time is not None else float("nan")
            fig.suptitle(self.args.title.format(time=time, step=frame.step), y=0.97)


def render(frames, args):
    """One picture of the last frame, or (output .gif) an animation of all frames."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scene = Scene(args, frames)
    fig, ax = scene.figure()
    if Path(args.output).suffix.lower() == ".gif":
        from PIL import Image

        # each frame's own 256-colour palette by median cut: the shades of one cloth colour
        # stay smooth (an RGBA frame written as it is gets a few colours and flat patches)
        images = []
        for frame in frames:
            scene.draw(fig, ax, frame)
            fig.canvas.draw()
            rgb = Image.fromarray(np.asarray(fig.canvas.buffer_rgba())[..., :3])
            images.append(rgb.quantize(256, method=Image.Quantize.MEDIANCUT,
                                       dither=Image.Dither.NONE))
        images[0].save(args.output, save_all=True, append_images=images[1:], loop=0,
                       duration=round(1000 / args.fps))
    else:
        scene.draw(fig, ax, frames[-1])
        fig.savefig(args.output, facecolor="white")
    plt.close(fig)


def parser():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+", metavar="file",
                    help="a .vtp, .vtu or .obj frame, several, or a .pvd series")
    ap.add_argument("-o", "--output",
                    help="picture (.png, .svg, .pdf) of the last frame, or animation (.gif) of "
                    "all; default: the first file's name with .png")
    ap.add_argument("--elev", type=float, default=25.0, help="camera elevation (degrees)")
    ap.add_argument("--azim", type=float, default=-60.0, help="camera azimuth (degrees)")
    ap.add_argument("--zoom", type=float, default=1.0, help="> 1 brings the mesh closer")
    ap.add_argument("--light", type=float, nargs=3, default=(0.4, 0.7, 1.0),
                    metavar=("RIGHT", "UP", "TOWARD"),
                    help="light direction in the camera's frame")
    ap.add_argument("--ambient", type=float, default=0.35, help="light without direction (0-1)")
    ap.add_argument("--color", default="#dcc08f", help="surface colour without --field")
    ap.add_argument("--mesh-colors", nargs="+", metavar="COLOR",
                    help="surface colour of mesh 1, 2, ... (repeated when there are more meshes)")
    ap.add_argument("--back-color", metavar="COLOR",
                    help="colour of the triangles seen from the side away from their normal")
    ap.add_argument("--field", help="colour by this point array of a .vtp/.vtu file")
    ap.add_argument("--cmap", default="viridis", help="colour map of --field")
    ap.add_argument("--range", type=float, nargs=2, metavar=("LO", "HI"),
                    help="field values at the ends of the colour map (default: min, max)")
    ap.add_argument("--label", help="colour bar label (default: the field's name)")
    ap.add_argument("--box", type=float, nargs=6, action="append",
                    metavar=("XLO", "XHI", "YLO", "YHI", "ZLO", "ZHI"),
                    help="a solid box drawn with the mesh (repeatable)")
    ap.add_argument("--box-color", default="#8a8f99", help="colour of the boxes")
    ap.add_argument("--stack", action="store_true",
                    help="draw the meshes one after the other in the order of their ids")
    ap.add_argument("--limits", type=float, nargs=6,
                    metavar=("XLO", "XHI", "YLO", "YHI", "ZLO", "ZHI"),
                    help="the region to show (default: the box holding every frame's mesh)")
    ap.add_argument("--title", help="title above the picture; {time} and {step} name the frame's")
    ap.add_argument("--size", type=float, nargs=2, default=(8.0, 6.0), metavar=("W", "H"),
                    help="picture size (inches)")
    ap.add_argument("--dpi", type=int, default=100)
    ap.add_argument("--fps", type=float, default=10.0, help="frames per second of a GIF")
    return ap


def main(argv=None):
    args = parser().parse_args(argv)
    args.output = args.output or str(Path(args.files[0]).with_suffix(".png"))
    try:
        paths = []
        for name in args.files:
            paths += series_files(name) if Path(name).suffix == ".pvd" else [Path(name)]
        frames = [read_mesh(p) for p in paths]
        for path, frame in zip(paths, frames):
            if len(frame.triangles) == 0:
                raise ValueError(f"{path}: no triangles")
        render(frames, args)
    except (ValueError, OSError, ET.ParseError) as e:
        print(f"render_mesh.py: {e}", file=sys.stderr)
        return 1
    what = f"{len(frames)} frames" if len(frames) > 1 else f"{len(frames[-1].triangles)} triangles"
    print(f"render_mesh.py: {args.output} ({what})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
