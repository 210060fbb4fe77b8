/* cocopp_ccx_hooks.h: where a ccx patched with scripts/calculix/05-coupled-increments.patch
 * hands control to cocopp's coupled ccx (`cocopp-ccx`, coupled_ccx.cpp) while it runs a step.
 *
 * C, because ccx's nonlingeo.c includes it; ccx's integers (ITG) are `int` in Debian's build
 * (no -DINTEGER8), so `int` here. A plain ccx leaves `cocopp_ccx_hooks` NULL and never calls.
 *
 * ccx's increment loop (nonlingeo.c) calls, with icutb == 0 (the last increment converged):
 *   increment_start:  at the top of every increment, after ccx copied its state into the
 *                     increment-start ("ini") arrays. At a coupling step's start the hook waits
 *                     for the coupler's loads and keeps the state as the step's checkpoint; it
 *                     sets the increment so that the coupling step's end is met exactly.
 *   apply_loads:      after ccx computed the increment's loads (tempload): the interface's loads
 *                     replace the placeholders the coupler's deck gave for them.
 *   increment_end:    after an increment converged, before ccx writes its results. At the
 *                     coupling step's end the hook returns the interface displacements to the
 *                     coupler and waits: another coupling iteration (the state is reset to the
 *                     checkpoint and the step repeated, no results written) or the step
 *                     committed (ccx writes its results and goes on).
 */
#ifndef COCOPP_CCX_HOOKS_H
#define COCOPP_CCX_HOOKS_H

#ifdef __cplusplus
extern "C" {
#endif

/* What increment_start and increment_end return. */
enum cocopp_ccx_action {
  COCOPP_CCX_CONTINUE = 0, /* go on with the increment (or, at its end, write results) */
  COCOPP_CCX_REPEAT = 1,   /* increment_end: the step's state was reset; skip the results */
  COCOPP_CCX_STOP = 2      /* the coupler stopped: end the step (theta is set to 1) */
};

/* Addresses of nonlingeo's variables, taken once before its increment loop. Arrays are given
 * by the address of ccx's pointer, since ccx may reallocate them. Sizes are read at each call. */
struct cocopp_ccx_increment {
  /* time within the ccx step: theta and dtheta are fractions of the step's period tper */
  double *theta, *dtheta, *tper, *ttime;
  int *iinc, *jprint;
  /* ccx's increment control: the reference increment and whether the last converged fast */
  double* dthetaref;
  int* istab;
  int *nk, *mt, *ne0, *nstate, *mi, *neq, *nboun, *nmethod, *ithermal, *nener;
  double** co;
  /* the mesh, for ccx's own mapping of its 3D expansion back onto 1D/2D elements' nodes */
  int **ipkon, **kon, *ne, *ielprop;
  char** lakon;
  double* prop;
  /* the state ccx's own cut-back restores (nonlingeo.c, "icutb!=0") */
  double **vold, **veold, **accold, **f, **fext, **fnext, **cv, **sti, **eme, **ener, **xstate,
      **xbounact, **t1act;
  double *allwk, *dampwk, *energy /* [4] */, *qam /* [2] */;
  /* ccx's mean force and energy of the step (the convergence check's scale) are running means
   * over its converged increments, jnz of them: a coupling iteration starts them afresh */
  int* jnz;
  double* energym;
};

struct cocopp_ccx_loads {
  /* concentrated loads (*CLOAD): node and direction per entry, actual values */
  int nforc;
  const int* nodeforc; /* (2, nforc): node, 0 */
  const int* ndirforc; /* direction 1..3 (0: heat) */
  double* xforcact;
  /* distributed loads (*DLOAD): element and label ("P3", 20 characters) per entry */
  int nload;
  const int* nelemload; /* (2, nload): element, 0 */
  const char* sideload;
  double* xloadact; /* (2, nload): value, 0 */
  double reltime;   /* theta + dtheta of the increment */
};

struct cocopp_ccx_hooks {
  enum cocopp_ccx_action (*increment_start)(struct cocopp_ccx_increment* increment);
  void (*apply_loads)(struct cocopp_ccx_increment* increment, struct cocopp_ccx_loads* loads);
  enum cocopp_ccx_action (*increment_end)(struct cocopp_ccx_increment* increment);
  /* Non-zero for a linear model (no NLGEOM, no nonlinear material; the wrapper decides):
     checkconvergence.c accepts a first Newton iteration whose residual meets the force
     criterion, where ccx always makes a second one to see the correction vanish. */
  int linear;
};

/* Defined in the patched nonlingeo.c; set by cocopp-ccx before it runs ccx. */
extern struct cocopp_ccx_hooks* cocopp_ccx_hooks;

#ifdef __cplusplus
}
#endif

#endif
