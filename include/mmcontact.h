/* The run's context, MMCtx: one struct per concern, each defined by its component's types header
 * (include/<component>types.h). */
#pragma once
#include "mmbase.h"
#include "apptypes.h"
#include "obstacle.h"
#include "fem.h"
#include "contact.h"
#include "friction.h"
#include "tstypes.h"
#include "io.h"

/* Everything the stepper needs; the TS type "newmark" holds a pointer to it. */
typedef struct _MMCtx {
  MMOptions   opt;
  MMMaterial  material;
  MMOperators op;
  MMLoads     loads;
  MMContact   contact;
  MMFriction  friction;
  MMNewmark   nm;       /* the stepper (src/ts/): owns the three below */
  MMState    *state;    /* borrowed from nm (MMNewmarkGetState), for the components not yet handed it */
  MMDamping  *damping;  /* borrowed from nm (MMNewmarkGetDamping) */
  MMHistory  *hist;     /* borrowed from nm (MMNewmarkGetHistory) */
  MMProgress  progress;
  MMOutput    out;
  MMCheckpoint ckpt;
} MMCtx;
