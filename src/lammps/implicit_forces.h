/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   What an implicit integrator (fix sissm) needs from the force model, each item below.
   pair_style peri/nosb implements it; fix sissm sees nothing else of the pair.
------------------------------------------------------------------------- */

#ifndef LMP_PERISISSM_IMPLICIT_FORCES_H
#define LMP_PERISISSM_IMPLICIT_FORCES_H

#include <string>

namespace PeriSISSM {
struct BondSprings;
struct HingeCouplings;
struct PlateCouplings;
}    // namespace PeriSISSM

namespace LAMMPS_NS {

class ImplicitForces {
 public:
  // an implicit step begins: until end_implicit_step() bonds do not break, and contact pairs
  // that couple an atom of groupbit with one outside it are noted (group_coupled())
  virtual void begin_implicit_step(int groupbit) = 0;
  virtual void end_implicit_step() = 0;

  // one force evaluation at the current positions (ghost positions current, forces zeroed by
  // the caller): adds the force densities to atom->f (ghost parts to be folded back by the
  // caller under newton on when ghost_forces() says there are any); block not null: also the
  // SISSM block sum_j omega_ij (H_i + H_j + (C_i + C_j)/2 I) of every owned atom (xx yy zz xy
  // xz yz) into block[i]
  virtual void evaluate(double **block) = 0;
  // true when the last evaluation wrote forces on ghost atoms (short-range contact)
  virtual bool ghost_forces() const = 0;
  // the bond-projected stiffness of the owned atoms' unbroken bonds in the current positions
  // (core peri/bond_stiffness.h), from the last evaluation with blocks: their partners, and
  // with values true also the springs' stiffnesses, directions and stabilization blocks
  virtual void bond_springs(PeriSISSM::BondSprings &springs, bool values) = 0;
  // the bending hinges with an owned vertex, each once (core peri/bond_stiffness.h; empty
  // without bending): their vertices and rows, and with gradients true also their gradients in
  // the current positions (grad left empty otherwise)
  virtual void hinge_couplings(PeriSISSM::HingeCouplings &hinges, bool gradients) = 0;
  // the plate bending stencils with an owned vertex, each once per rank (core
  // peri/bond_stiffness.h; empty without them): their vertices, rows and constant factors,
  // valid until the next force evaluation
  virtual const PeriSISSM::PlateCouplings &plate_couplings() = 0;

  // contact candidates while an implicit step moves the atoms: track_contact_motion(1) at
  // init; contact_follow_motion() after every move (ghost positions current) re-selects the
  // candidates when needed (1), has nothing to do (0), or finds the atoms moved farther than the
  // neighbor list covers (-1: the candidates are incomplete for this iterate);
  // contact_end_of_step() stops with an error when the step's result is that far (cause: what
  // the integrator knows about the step, may be empty) and returns true when the next step
  // should start from a new neighbor list
  // contact_build_wanted() asks how a (sub-)step should start at the current positions: 0 from
  // the current candidates, 1 from a new neighbor list, 2 (also) the candidates are incomplete
  // here (all ranks)
  virtual void track_contact_motion(int flag) = 0;
  virtual int contact_follow_motion() = 0;
  virtual bool contact_end_of_step(const std::string &cause) = 0;
  virtual int contact_build_wanted() = 0;

  // true (all ranks) when an unbroken bond joins an owned atom of groupbit with an atom outside
  // it, or a contact pair did in the evaluations since begin_implicit_step()
  virtual bool group_coupled(int groupbit) = 0;

  // the blow-up guard once the integrator has moved the atoms: converged 1 (the step
  // converged), 0 (it did not), -1 (explicit)
  virtual void check_motion(int converged) = 0;

  // true (all ranks) when some owned atom of groupbit is a particle of a membrane type without
  // bending: the coarse level's matrix has no stiffness out of its plane but the mass (fix
  // sissm's default preconditioner is then block). Membranes outside the group (held, moved
  // by other fixes) are not unknowns of the fix and do not count.
  virtual bool has_unbent_membranes(int groupbit) = 0;
  // true (all ranks) when every owned atom of groupbit is a particle of a membrane type
  // (precond amg then aggregates without smoothing the interpolation: fix_sissm_amg.cpp)
  virtual bool only_membranes(int groupbit) = 0;

 protected:
  // not deleted through this interface (its implementations are LAMMPS styles whose
  // destructors may throw)
  ~ImplicitForces() = default;
};

}    // namespace LAMMPS_NS

#endif
