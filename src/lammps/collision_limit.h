/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   What an implicit integrator (fix sissm) needs from a contact model: collision-free steps
   (continuous collision detection), the start of each step (lagged friction), the contact's
   diagonal stiffness blocks for the SISSM blocks, and for a contact that adapts its stiffness
   (kappa auto: IPC's adaptive barrier stiffness) its solver's iterates and residual. fix
   nosb/contact implements it; fix sissm finds it among the fixes whose forces it re-evaluates
   at every iterate.

   The integrator keeps its atoms on a path of admissible positions: begin_path() at a step's
   start, limit_move() before every force evaluation and at the step's end. Every position it
   evaluates or ends a step at is then connected to the step's start by straight moves on which
   no pair comes within the contact's thickness.
------------------------------------------------------------------------- */

#ifndef LMP_PERISISSM_COLLISION_LIMIT_H
#define LMP_PERISISSM_COLLISION_LIMIT_H

namespace LAMMPS_NS {

class CollisionLimit {
 public:
  // false when this contact does not limit moves (then the calls below begin_step() are not
  // made)
  virtual bool limits_moves() const = 0;
  // the start of an implicit (sub-)step of length h (> 0), called right before begin_path()
  // whether or not the contact limits moves: the current positions (owned and ghost, current)
  // are x^n, and the force evaluations up to the next begin_step() are the iterates of this
  // step (and the one after it, at its result). c is the scheme's force factor (h^2 for
  // backward Euler): the step's inertial scale is rho / c. Collective.
  virtual void begin_step(double h, double c) = 0;
  // the current positions (owned and ghost, current) are admissible: the reference of the next
  // move. Collective.
  virtual void begin_path() = 0;
  // the move from the reference to the current positions (owned and ghost current): returns
  // the largest fraction t in [0, 1] of it on which no pair comes within the thickness and no
  // atom leaves the candidates' reach (the same on all ranks), after moving the owned atoms of
  // groupbit back to reference + t (current - reference) when t < 1 (the caller then brings the
  // ghosts up to date and calls begin_path()). Collective.
  virtual double limit_move(int groupbit) = 0;
  // true when the last limit_move() was cut short by how far the contact candidates reach (the
  // atoms cannot move farther inside this step), not by a pair coming close
  virtual bool reach_limited() const = 0;
  // the error for a step that ended cut short by the candidates' reach (collective)
  virtual void reach_error(const char *integrator) = 0;
  // true (all ranks) when the next step should start from a new neighbor list (the atoms moved
  // far enough from the last build to shorten the next step's reach): end_of_step at the end
  // of a step (its motion may predict the next one's), else before a sub-step. Collective.
  virtual bool rebuild_wanted(bool end_of_step) = 0;
  // keep what add_blocks() needs of the last force evaluation (called after the evaluations
  // whose blocks the solver may ask for)
  virtual void keep_blocks() = 0;
  // add the positive semi-definite diagonal blocks of the contact's stiffness at the evaluation
  // of the last keep_blocks(), per unit volume of each owned atom (xx yy zz xy xz yz), to
  // block (later evaluations, Jacobian probes, do not change them)
  virtual void add_blocks(double **block) = 0;

  // true when the contact adapts its stiffness (then the three calls below are made, and the
  // contact must be re-evaluated at every iterate)
  virtual bool adapts_stiffness() const = 0;
  // at the integrator's init (every run): the force factor of its steps of the run's time step,
  // for the force evaluations before the first step
  virtual void set_force_factor(double c) = 0;
  // the next force evaluation is at an iterate of the solver (not a probe of a Jacobian-vector
  // product): the contact may change its stiffness only there. Collective.
  virtual void next_iterate() = 0;
  // after the first evaluation of a (sub-)step: res the residual of the integrator's group
  // (owned atoms of groupbit), r_i = rho_i (yhat_i - y_i) + c f_i (rho the mass density, f the
  // force density of everything the step includes, the contact too), so that -r_i V_i / c is
  // the gradient of the step's incremental potential at atom i; c the force factor. Returns
  // true (all ranks) when the stiffness changed: the evaluation must then be redone.
  // Collective.
  virtual bool balance_stiffness(double **res, double c, int groupbit) = 0;

 protected:
  ~CollisionLimit() = default;
};

}    // namespace LAMMPS_NS

#endif
