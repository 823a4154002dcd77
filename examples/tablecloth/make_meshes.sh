#!/bin/sh
# Make the tablecloth meshes (examples/tablecloth/README.md): a 1.2 m square of near-equilateral
# triangles (tools/make_sheet.py --pattern equilateral: the bending term is isotropic only on
# equilateral triangles), centred at the origin in the plane z = 0.
#   ./make_meshes.sh        the CI mesh, cloth_ci.obj: 4 cm triangles, 1134 vertices, 2135 faces
#                           (shipped)
#   ./make_meshes.sh full   the authors' size, cloth_full.obj: 6.5 mm triangles, 39911 vertices,
#                           79023 faces (theirs: 40.0K / 79.2K); not shipped (3 MB)
#   ./make_meshes.sh A      any spacing A (m), cloth_A.obj
# The deck needs the spacing as -var a (the horizon and the neighbor skin are multiples of it).
set -e
cd "$(dirname "$0")"
SHEET=../../tools/make_sheet.py
case "${1:-ci}" in
  ci)   a=0.04;   out=cloth_ci.obj ;;
  full) a=0.0065; out=cloth_full.obj ;;
  *)    a=$1;     out=cloth_$1.obj ;;
esac
python3 "$SHEET" rectangle 1.2 1.2 --spacing "$a" --pattern equilateral -o "$out"
echo "run it with: ../../build/lmp -in in.tablecloth -var mesh $out -var a $a"
