/* The run's context, MMCtx: one struct per concern, each defined by its component's types header
 * (include/<component>types.h). */
#pragma once
#include "mmbase.h"
#include "apptypes.h"
#include "obstacle.h"
#include "fem.h"
#include "contact.h"
#include "friction.h"
#include "ts.h"
#include "io.h"

/* Everything the stepper needs; the TS type "newmark" holds a pointer to it. */
typedef struct _MMCtx {
  MMOptions   opt;
  MMMaterial  material;
  MMOperators op;
  MMLoads     loads;
  MMContact   contact;
  MMFriction  friction;
  MMNewmark   nm; /* the stepper (src/ts/): its state, history and damping through MMNewmarkGet* */
  MMProgress  progress;
  MMOutput    out;
  MMCheckpoint ckpt;
} MMCtx;
