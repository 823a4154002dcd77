"""The deck set-up the pair_coeff tests share: a 6 x 6 x 6 simple cubic block of peri particles
(spacing 1 mm, SI units, free boundaries) in a box of two atom types, all created as type 1,
with density 1000 and volume 1e-9 (the particle spacing cubed)."""

TWO_TYPE_BLOCK = """
units           si
boundary        s s s
atom_style      peri
atom_modify     map array
lattice         sc 0.001
region          block block -0.5 5.5 -0.5 5.5 -0.5 5.5
create_box      2 block
create_atoms    1 region block
set             group all density 1000
set             group all volume 1.0e-9
"""
