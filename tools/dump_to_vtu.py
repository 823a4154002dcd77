#!/usr/bin/env python3
"""Convert a LAMMPS `dump custom` text file into VTK point clouds for ParaView: one ASCII .vtu
file per frame (every particle a vertex cell, every other column a point array) and a .pvd
series listing them with their timesteps.

    python3 tools/dump_to_vtu.py dump.atoms                  # dump.atoms.STEP.vtu, dump.atoms.pvd
    python3 tools/dump_to_vtu.py dump.atoms -o frames/atoms  # frames/atoms.STEP.vtu, .pvd

The dump needs the columns x y z (or xu yu zu); the others (id, type, c_ID[I], v_name, ...)
become point arrays of the same names, Int64 for id, type, mol and proc, Float64 otherwise.
The numbers are written as the dump printed them, so the .vtu files hold the dump's values
exactly. (LAMMPS's own dump custom/vtk needs the VTK package and the VTK library; this build of
LAMMPS has neither. OVITO opens the dump file itself.) Open the .pvd in ParaView and show the
points as Point Gaussian or Points, coloured by a column. Python standard library only.
"""
import argparse
import sys
from pathlib import Path

INTEGER = {"id", "type", "mol", "proc", "procp1"}


def read_dump(path):
    """[(timestep, columns, rows)] of every frame of a dump custom text file, rows as lists of
    the printed words."""
    frames = []
    lines = Path(path).read_text().splitlines()
    k = 0
    while k < len(lines):
        if not lines[k].startswith("ITEM: TIMESTEP"):
            k += 1
            continue
        step = int(lines[k + 1])
        if not lines[k + 2].startswith("ITEM: NUMBER OF ATOMS"):
            raise ValueError(f"{path}: no NUMBER OF ATOMS after timestep {step}")
        n = int(lines[k + 3])
        head = k + 4
        while head < len(lines) and not lines[head].startswith("ITEM: ATOMS"):
            head += 1
        if head == len(lines):
            raise ValueError(f"{path}: no ITEM: ATOMS line in timestep {step}")
        columns = lines[head].split()[2:]
        rows = [line.split() for line in lines[head + 1:head + 1 + n]]
        if len(rows) != n or any(len(r) != len(columns) for r in rows):
            raise ValueError(f"{path}: timestep {step}: {n} rows of {len(columns)} columns "
                             "expected")
        frames.append((step, columns, rows))
        k = head + 1 + n
    if not frames:
        raise ValueError(f"{path}: not a LAMMPS dump file (no ITEM: TIMESTEP)")
    return frames


def position_columns(columns):
    for names in (("x", "y", "z"), ("xu", "yu", "zu")):
        if all(c in columns for c in names):
            return [columns.index(c) for c in names]
    raise ValueError(f"the dump has no x y z (or xu yu zu) columns (columns: {' '.join(columns)})")


def vtu_text(columns, rows):
    """The .vtu file of one frame."""
    pos = position_columns(columns)
    n = len(rows)
    out = ['<?xml version="1.0"?>',
           '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" '
           'header_type="UInt64">',
           "  <UnstructuredGrid>",
           f'    <Piece NumberOfPoints="{n}" NumberOfCells="{n}">',
           "      <PointData>"]
    for c, name in enumerate(columns):
        if c in pos:
            continue
        kind = "Int64" if name in INTEGER else "Float64"
        out.append(f'        <DataArray type="{kind}" Name="{name}" format="ascii">')
        out.append("          " + " ".join(r[c] for r in rows))
        out.append("        </DataArray>")
    out += ["      </PointData>", "      <Points>",
            '        <DataArray type="Float64" NumberOfComponents="3" format="ascii">']
    out += ["          " + " ".join(r[c] for c in pos) for r in rows]
    out += ["        </DataArray>", "      </Points>", "      <Cells>",
            '        <DataArray type="Int64" Name="connectivity" format="ascii">',
            "          " + " ".join(map(str, range(n))),
            "        </DataArray>",
            '        <DataArray type="Int64" Name="offsets" format="ascii">',
            "          " + " ".join(map(str, range(1, n + 1))),
            "        </DataArray>",
            '        <DataArray type="UInt8" Name="types" format="ascii">',
            "          " + " ".join(["1"] * n),    # VTK_VERTEX
            "        </DataArray>", "      </Cells>", "    </Piece>", "  </UnstructuredGrid>",
            "</VTKFile>", ""]
    return "\n".join(out)


def pvd_text(entries):
    """The .pvd series of (timestep, file name relative to the series) entries."""
    out = ['<?xml version="1.0"?>', '<VTKFile type="Collection" version="1.0">', "  <Collection>"]
    out += [f'    <DataSet timestep="{step}" part="0" file="{name}"/>' for step, name in entries]
    out += ["  </Collection>", "</VTKFile>", ""]
    return "\n".join(out)


def convert(dump, prefix):
    """Write PREFIX.STEP.vtu for every frame and PREFIX.pvd; returns the .vtu paths."""
    prefix = Path(prefix)
    prefix.parent.mkdir(parents=True, exist_ok=True)
    entries, paths = [], []
    for step, columns, rows in read_dump(dump):
        path = prefix.parent / f"{prefix.name}.{step}.vtu"
        path.write_text(vtu_text(columns, rows))
        entries.append((step, path.name))
        paths.append(path)
    prefix.parent.joinpath(prefix.name + ".pvd").write_text(pvd_text(entries))
    return paths


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dump", help="a dump custom text file (one or more frames)")
    ap.add_argument("-o", "--prefix", help="output prefix (default: the dump's name)")
    args = ap.parse_args(argv)
    try:
        paths = convert(args.dump, args.prefix or args.dump)
    except (ValueError, OSError) as e:
        print(f"dump_to_vtu.py: {e}", file=sys.stderr)
        return 1
    series = Path(args.prefix or args.dump)
    print(f"dump_to_vtu.py: {len(paths)} frames, {series.parent / (series.name + '.pvd')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
